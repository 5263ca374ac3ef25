#!/bin/sh
# Installs what libcbr needs to build and test on Debian 12, from Debian's
# packages only. Runs apt-get as root, through sudo when not root.
set -e
packages="cmake g++ gfortran make pkg-config libeigen3-dev libopenmesh-dev doctest-dev libgmp-dev"
if [ "$(id -u)" -eq 0 ]; then as_root=""; else as_root="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$as_root apt-get update -qq
# shellcheck disable=SC2086
$as_root apt-get install -y -qq $packages >/dev/null
echo "setup-debian: installed $packages"
