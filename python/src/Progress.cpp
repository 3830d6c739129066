// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "Progress.h"

#include <strata/Error.h>

#include <algorithm>

namespace strata::python {

PythonProgress::PythonProgress(py::object callback)
    : mCallback(std::move(callback))
{
    if (!mCallback.is_none() && !PyCallable_Check(mCallback.ptr())) {
        throw Error(ErrorKind::BadInput, "progress must be callable (progress(fraction)) or None", {"", 0, "progress"});
    }
}

PythonProgress::~PythonProgress() = default;

bool PythonProgress::operator()(double fraction)
{
    py::gil_scoped_acquire acquire;
    if (mError) return false;
    try {
        // Ctrl-C sets a flag that only the main thread's signal check turns
        // into KeyboardInterrupt; the library calls back on the caller's
        // thread, so this is the place.
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (mCallback.is_none()) return true;
        const py::object answer = mCallback(std::clamp(fraction, 0.0, 1.0));
        if (!answer.is_none() && !answer.cast<bool>()) {
            PyErr_SetString(PyExc_KeyboardInterrupt, "stopped: progress() returned False");
            throw py::error_already_set();
        }
        return true;
    } catch (py::error_already_set& error) {
        mError.emplace(std::move(error));
        return false;
    } catch (const py::cast_error&) {
        // The callable's answer is not a truth value.
        PyErr_SetString(PyExc_TypeError, "progress() must return None, True or False");
        mError.emplace();
        return false;
    }
}

void PythonProgress::raiseStored()
{
    if (!mError) return;
    py::error_already_set error = std::move(*mError);
    mError.reset();
    throw error;
}

} // namespace strata::python
