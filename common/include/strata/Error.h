// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The one exception type Strata throws for failures a user can cause or see:
/// a bad scene file, a missing input, no GL context, a shader that does not
/// compile, a write that fails. Broken preconditions inside the library are
/// asserts, not errors.
///
/// An Error carries a kind, so a program can react without reading the text
/// (the CLI maps BadInput to exit code 2, Interrupted to 130 and every other
/// kind to 1), and the
/// place it is about where known (file, line, key, value), so a caller can
/// point at it without parsing the message.

#include <stdexcept>
#include <string>
#include <utility>

namespace strata {

/// What went wrong, in the terms a caller acts on.
enum class ErrorKind
{
    BadInput, ///< the input is wrong: a scene value, a flag, a file that is not what it claims; fix the input
    Io,       ///< the system failed us: a write, a rename, a full disk, a folder we cannot create
    Gl,       ///< the GL driver failed: no context, a shader that does not compile, a GL error
    Internal,    ///< a bug or an exhausted resource inside Strata
    Interrupted, ///< the caller asked a long operation to stop (a progress callback returned false)
};

/// "bad input", "I/O", "GL", "internal" or "interrupted".
inline const char* errorKindName(ErrorKind kind)
{
    switch (kind) {
    case ErrorKind::BadInput: return "bad input";
    case ErrorKind::Io: return "I/O";
    case ErrorKind::Gl: return "GL";
    case ErrorKind::Internal: return "internal";
    case ErrorKind::Interrupted: return "interrupted";
    }
    return "internal";
}

/// Where an error is about; every field is optional (empty or 0 = unknown).
struct ErrorPlace
{
    std::string file{};  ///< the file being read or written ("<default scene>" for embedded text)
    int line = 0;      ///< 1-based line in `file`, 0 = unknown
    std::string key{};   ///< the scene key, e.g. "terrain.nodes.land.amplitude", or the flag
    std::string value{}; ///< the offending value as the user wrote it
};

/// A failure the user can fix or must be told about. `what()` says what went
/// wrong and where (file, line, key, value) in one line, ready to print as
/// is; kind() and place() say the same for programs.
class Error : public std::runtime_error
{
public:
    /// An error of `kind` with a complete message. There is no default kind:
    /// the kind decides the CLI's exit code, so every throw site names it.
    Error(ErrorKind kind, const std::string& message, ErrorPlace place = {})
        : std::runtime_error(message), mKind(kind), mPlace(std::move(place))
    {
    }

    ErrorKind kind() const { return mKind; }
    const ErrorPlace& place() const { return mPlace; }

private:
    ErrorKind mKind;
    ErrorPlace mPlace;
};

} // namespace strata
