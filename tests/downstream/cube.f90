! Downstream test, Fortran: compiled the way a user does,
!     gfortran -I$(pkg-config --variable=fmoddir cbr) cube.f90 \
!              $(pkg-config --libs cbr)
! against an installed libcbr and its installed module cbr.mod, and run.
!
! Same cube as cube.c (8 corners + centre: 12 tetrahedra, all coned to the
! centre), with 1-based ids (CBR_PARAM_INDEX_BASE = 1): every returned id
! must be in 1..9 and the centre is id 9. Stops with a non-zero code on any
! mismatch.
program cube
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_int64_t, c_double, &
                                         c_associated, c_null_ptr
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use cbr
  implicit none

  type(c_ptr) :: mesh
  real(c_double) :: xyz(3, 9), xyz_back(3, 9), bad(3, 2), base, vol6, total
  integer(c_int64_t), allocatable :: tets(:, :)
  integer(c_int64_t) :: ntet
  integer(c_int) :: status
  integer :: failures, t, k
  character(len=32) :: expected
  character(len=:), allocatable :: version, message
  logical :: seen(9)

  failures = 0

  ! Version: the library loaded agrees with the module's constants.
  version = cbr_f_string(cbr_version())
  write (expected, '(i0, ".", i0, ".", i0)') CBR_VERSION_MAJOR, &
      CBR_VERSION_MINOR, CBR_VERSION_PATCH
  call check(version == trim(expected), "cbr_version() = '" // version // &
             "', module says " // trim(expected))
  call check(len(cbr_f_string(cbr_status_string(CBR_ERR_INVALID_INPUT))) > 0, &
             "cbr_status_string is empty")

  mesh = c_null_ptr
  status = cbr_mesh_create(mesh)
  if (status /= CBR_OK .or. .not. c_associated(mesh)) then
    print *, "cbr_mesh_create failed: ", status
    error stop 1
  end if

  status = cbr_mesh_set_param(mesh, CBR_PARAM_INDEX_BASE, 1.0_c_double)
  call check(status == CBR_OK, "set CBR_PARAM_INDEX_BASE = 1")
  status = cbr_mesh_get_param(mesh, CBR_PARAM_INDEX_BASE, base)
  call check(status == CBR_OK .and. base == 1.0_c_double, &
             "get CBR_PARAM_INDEX_BASE gives 1")

  xyz = reshape([0d0, 0d0, 0d0,  1d0, 0d0, 0d0,  0d0, 1d0, 0d0,  1d0, 1d0, 0d0, &
                 0d0, 0d0, 1d0,  1d0, 0d0, 1d0,  0d0, 1d0, 1d0,  1d0, 1d0, 1d0, &
                 0.5d0, 0.5d0, 0.5d0], [3, 9])
  status = cbr_mesh_insert_points(mesh, 9_c_int64_t, xyz)
  call check(status == CBR_OK, "insert 9 points: " // &
             cbr_f_string(cbr_mesh_last_error(mesh)))
  call check(cbr_mesh_point_count(mesh) == 9, "point count is 9")
  status = cbr_mesh_get_points(mesh, xyz_back)
  call check(status == CBR_OK .and. all(xyz_back == xyz), &
             "points read back identical")

  ntet = cbr_mesh_tet_count(mesh)
  if (ntet /= 12) then
    print '(a, i0, a)', "cbr_mesh_tet_count = ", ntet, ", expected 12"
    error stop 1
  end if
  allocate (tets(4, ntet))
  tets = -1
  status = cbr_mesh_get_tets(mesh, tets)
  call check(status == CBR_OK, "cbr_mesh_get_tets")
  if (any(tets < 1 .or. tets > 9)) then
    print '(a)', "ids out of 1..9 with CBR_PARAM_INDEX_BASE = 1:"
    print '(4(1x, i0))', tets
    error stop 1
  end if

  seen = .false.
  total = 0
  do t = 1, int(ntet)
    do k = 1, 4
      seen(tets(k, t)) = .true.
    end do
    call check(any(tets(:, t) == 9), "every tetrahedron has the centre (id 9)")
    vol6 = six_volume(xyz(:, tets(1, t)), xyz(:, tets(2, t)), &
                      xyz(:, tets(3, t)), xyz(:, tets(4, t)))
    call check(vol6 == 0.5d0, "6 * volume = 0.5, positively oriented")
    total = total + vol6 / 6
  end do
  call check(all(seen), "every point is a vertex")
  call check(abs(total - 1) < 1d-12, "the volumes add up to 1")

  ! A NaN is rejected and changes nothing.
  bad = 0.25d0
  bad(2, 2) = ieee_value(bad(2, 2), ieee_quiet_nan)
  status = cbr_mesh_insert_points(mesh, 2_c_int64_t, bad)
  call check(status == CBR_ERR_INVALID_INPUT, "a NaN gives CBR_ERR_INVALID_INPUT")
  message = cbr_f_string(cbr_mesh_last_error(mesh))
  call check(len(message) > 0, "the NaN error has a message")
  call check(cbr_mesh_point_count(mesh) == 9 .and. cbr_mesh_tet_count(mesh) == 12, &
             "a failed insertion changes nothing")

  call cbr_mesh_destroy(mesh)

  if (failures /= 0) then
    print '(a, i0, a)', "cube.f90: ", failures, " check(s) failed"
    error stop 1
  end if
  print '(a)', "cube.f90: libcbr " // version // &
      ", 1-based ids, 12 tetrahedra, NaN rejected: OK"
  ! Variables of the main program are never freed implicitly (leak checkers).
  deallocate (tets, version, message)

contains

  subroutine check(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (.not. ok) then
      print '(a)', "cube.f90: check failed: " // what
      failures = failures + 1
    end if
  end subroutine check

  ! 6 * signed volume of the tetrahedron (a, b, c, d): det[b-a, c-a, d-a].
  function six_volume(a, b, c, d) result(v)
    real(c_double), intent(in) :: a(3), b(3), c(3), d(3)
    real(c_double) :: v, u(3), w(3), z(3)
    u = b - a
    w = c - a
    z = d - a
    v = u(1) * (w(2) * z(3) - w(3) * z(2)) - u(2) * (w(1) * z(3) - w(3) * z(1)) &
        + u(3) * (w(1) * z(2) - w(2) * z(1))
  end function six_volume

end program cube
