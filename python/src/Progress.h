// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once

/// \file
/// A long library call's progress, seen from Python: the library calls it
/// with the GIL released (from the thread that made the call); it takes the
/// GIL, checks for Ctrl-C and calls the user's `progress(fraction)`. A
/// Ctrl-C, an exception in the callable or a False return stops the call
/// (the library throws strata::Error, Interrupted); finish() then raises
/// the Python exception that stopped it.

#include "Bindings.h"

#include <strata/Error.h>
#include <strata/scene/Pipeline.h>

#include <optional>

namespace strata::python {

class PythonProgress
{
public:
    /// `callback`: None or a callable taking a float in [0, 1].
    explicit PythonProgress(py::object callback);
    ~PythonProgress();

    /// For the library: false stops the call.
    bool operator()(double fraction);

    /// Runs `call` with the GIL released. When it stops on an interruption
    /// this object caused, raises the Python exception behind it
    /// (KeyboardInterrupt for Ctrl-C or a False return); other errors pass.
    template <class Call> auto run(Call&& call)
    {
        try {
            py::gil_scoped_release release;
            return call();
        } catch (const Error& error) {
            if (error.kind() == ErrorKind::Interrupted) raiseStored();
            throw;
        }
    }

private:
    void raiseStored();

    py::object mCallback;
    std::optional<py::error_already_set> mError;
};

/// A PipelineObserver that reports to a PythonProgress (the bake).
class PythonObserver final : public scene::PipelineObserver
{
public:
    explicit PythonObserver(PythonProgress& progress) : mProgress(progress) {}
    bool progress(double fraction) override { return mProgress(fraction); }

private:
    PythonProgress& mProgress;
};

} // namespace strata::python
