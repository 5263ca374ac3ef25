// Exceptions of the core. They never cross the C API: capi/ catches every
// exception and turns it into a status code and a message.
#pragma once

#include <stdexcept>

namespace cbr {

// A consistency check inside libcbr failed: a bug (CBR_ERR_INTERNAL).
struct InternalError : std::logic_error {
    using std::logic_error::logic_error;
};

}  // namespace cbr
