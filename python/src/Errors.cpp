// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// strata::Error kinds as Python exceptions. A caller catches the built-in
// class it already knows (ValueError, OSError, RuntimeError) and finds the
// place the error is about as attributes instead of parsing the message.

#include "Bindings.h"

#include <strata/Error.h>

#include <Python.h>

namespace strata::python {

namespace {

// Created once in bindErrors(); alive as long as the module (held by it).
PyObject* gBadInput = nullptr;
PyObject* gFileError = nullptr;
PyObject* gGlError = nullptr;

PyObject* newExceptionClass(py::module_& m, const char* name, PyObject* base, const char* doc)
{
    const std::string qualified = std::string("strata.") + name;
    PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
    if (!type) throw py::error_already_set();
    m.add_object(name, py::handle(type)); // steals nothing: add_object increfs
    return type;
}

py::object placeValue(const std::string& text) { return text.empty() ? py::none() : py::object(py::str(text)); }

void raise(PyObject* type, const Error& error)
{
    py::object instance = py::reinterpret_steal<py::object>(PyObject_CallOneArg(type, py::str(error.what()).ptr()));
    if (!instance) return; // the constructor's own exception stands
    const ErrorPlace& place = error.place();
    if (type == gFileError) {
        instance.attr("filename") = placeValue(place.file);
    } else {
        instance.attr("file") = placeValue(place.file);
        instance.attr("line") = place.line > 0 ? py::object(py::int_(place.line)) : py::none();
        instance.attr("key") = placeValue(place.key);
        instance.attr("value") = placeValue(place.value);
    }
    instance.attr("kind") = py::str(errorKindName(error.kind()));
    PyErr_SetObject(type, instance.ptr());
}

} // namespace

void bindErrors(py::module_& m)
{
    gBadInput = newExceptionClass(m, "BadInputError", PyExc_ValueError,
                                  "The input is wrong: a scene value, an argument, a file that is not what it claims.\n"
                                  "Attributes: file, line, key, value (None where unknown), kind.");
    gFileError = newExceptionClass(m, "FileError", PyExc_OSError,
                                   "The system failed a read or write (a full disk, a folder that cannot be created).\n"
                                   "Attributes: filename, kind.");
    gGlError = newExceptionClass(m, "GLError", PyExc_RuntimeError,
                                 "The GL driver failed: no EGL context, a shader that does not compile.\n"
                                 "Attributes: file, line, key, value, kind.");

    py::register_exception_translator([](std::exception_ptr thrown) {
        try {
            if (thrown) std::rethrow_exception(thrown);
        } catch (const Error& error) {
            switch (error.kind()) {
            case ErrorKind::BadInput: raise(gBadInput, error); return;
            case ErrorKind::Io: raise(gFileError, error); return;
            case ErrorKind::Gl: raise(gGlError, error); return;
            case ErrorKind::Interrupted: PyErr_SetString(PyExc_KeyboardInterrupt, error.what()); return;
            case ErrorKind::Internal: PyErr_SetString(PyExc_RuntimeError, error.what()); return;
            }
            PyErr_SetString(PyExc_RuntimeError, error.what());
        }
    });
}

} // namespace strata::python
