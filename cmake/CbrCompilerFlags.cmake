# Warnings and sanitizers for every target of this project.
set(CBR_WARNING_FLAGS -Wall -Wextra -Wpedantic -Wshadow -Wconversion-null)
if(CBR_WERROR)
  list(APPEND CBR_WARNING_FLAGS -Werror)
endif()

# Exact predicates need IEEE double arithmetic as written: no contraction of
# a*b+c into an fma (it would change rounding in the error-free
# transformations), no fast-math.
set(CBR_FP_FLAGS -ffp-contract=off -fno-fast-math)

if(CBR_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined -fno-sanitize-recover=all)
endif()

# Everything is hidden unless marked CBR_API.
set(CMAKE_CXX_VISIBILITY_PRESET hidden)
set(CMAKE_C_VISIBILITY_PRESET hidden)
set(CMAKE_VISIBILITY_INLINES_HIDDEN ON)
set(CMAKE_POSITION_INDEPENDENT_CODE ON)
