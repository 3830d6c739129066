#pragma once
/// \file
/// The one exception type Strata throws for failures a user can cause: a bad
/// scene file, a missing input, no GL context, a shader that does not compile.
/// Broken preconditions inside the library are asserts, not errors.

#include <stdexcept>
#include <string>

namespace strata {

/// A failure the user can fix. `what()` says what went wrong and where
/// (file, line, key, value) in one line, ready to print as is.
class Error : public std::runtime_error
{
public:
    explicit Error(const std::string& message)
        : std::runtime_error(message)
    {
    }
};

} // namespace strata
