// The object behind the opaque cbr_mesh handle, and the exception firewall
// every extern "C" function runs its body in.
#pragma once

#include <cbr/cbr.h>

#include <new>
#include <stdexcept>
#include <string>

#include "delaunay/delaunay.hpp"
#include "mesh/errors.hpp"

struct cbr_mesh {
    cbr::delaunay::Delaunay delaunay;
    int index_base = 0;
    // Message of the last failed call; mutable so that const queries can
    // report their own failures.
    mutable std::string last_error;
};

namespace cbr::capi {

// An error found by an argument or input check: status and message.
struct ApiError {
    int status;
    std::string message;
};

inline int fail(const cbr_mesh* mesh, const char* function, int status, const std::string& message) {
    if (mesh) {
        try {
            mesh->last_error = std::string(function) + ": " + message;
        } catch (...) {
            // No memory even for the message: keep the previous one.
        }
    }
    return status;
}

// Runs body() (returning a status) so that no exception leaves the library.
template <class Body>
int guarded(const cbr_mesh* mesh, const char* function, Body&& body) noexcept {
    try {
        return body();
    } catch (const ApiError& e) {
        return fail(mesh, function, e.status, e.message);
    } catch (const std::bad_alloc&) {
        return fail(mesh, function, CBR_ERR_OUT_OF_MEMORY, "out of memory");
    } catch (const std::length_error& e) {
        return fail(mesh, function, CBR_ERR_OUT_OF_MEMORY, std::string("capacity exceeded: ") + e.what());
    } catch (const cbr::InternalError& e) {
        return fail(mesh, function, CBR_ERR_INTERNAL, std::string("internal error: ") + e.what());
    } catch (const std::exception& e) {
        return fail(mesh, function, CBR_ERR_INTERNAL, std::string("internal error: ") + e.what());
    } catch (...) {
        return fail(mesh, function, CBR_ERR_INTERNAL, "internal error: unknown exception");
    }
}

inline void require(bool condition, int status, const std::string& message) {
    if (!condition) throw ApiError{status, message};
}

}  // namespace cbr::capi
