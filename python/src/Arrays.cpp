// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Python values into library values, with errors that name the argument.

#include "Bindings.h"

#include <strata/Error.h>

#include <cmath>

namespace strata::python {

glm::dvec3 toVec3(const py::handle& value, const char* what)
{
    const auto bad = [&] {
        return Error(ErrorKind::BadInput,
                     std::string(what) + " must be three finite numbers (x, y, z), not " +
                         std::string(py::repr(value)),
                     {"", 0, what, std::string(py::str(value))});
    };
    if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value)) throw bad();
    const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
    if (items.size() != 3) throw bad();
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i) {
        try {
            v[i] = items[i].cast<double>();
        } catch (const py::cast_error&) {
            throw bad();
        }
        if (!std::isfinite(v[i])) throw bad();
    }
    return v;
}

py::tuple fromVec3(const glm::dvec3& v) { return py::make_tuple(v.x, v.y, v.z); }

namespace {

std::string knobText(const std::string& key, const py::handle& value)
{
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "on" : "off";
    if (py::isinstance<py::str>(value) || py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) {
        return std::string(py::str(value));
    }
    throw Error(ErrorKind::BadInput, key + " must be a number, a string or a bool, not " + std::string(py::repr(value)),
                {"", 0, key, std::string(py::repr(value))});
}

void addKnob(const std::string& key, const py::handle& value, scene::QualityOverrides& out)
{
    const std::string text = knobText(key, value);
    try {
        out[key] = scene::checkKnob(key, text);
    } catch (const Error& error) {
        throw Error(error.kind(), error.what(), {"", 0, key, text});
    }
}

} // namespace

scene::QualityOverrides qualityOverrides(const py::dict& knobs, const py::object& quality)
{
    scene::QualityOverrides out;
    if (!quality.is_none()) {
        if (!py::isinstance<py::dict>(quality)) {
            throw Error(ErrorKind::BadInput, "quality must be a dict of knobs, e.g. {'mesher': 'surface-nets'}",
                        {"", 0, "quality"});
        }
        for (const auto& [key, value] : quality.cast<py::dict>()) addKnob(py::str(key), value, out);
    }
    for (const auto& [key, value] : knobs) {
        if (!value.is_none()) addKnob(py::str(key), value, out);
    }
    if (out.count("voxel_size") && out.count("voxel_scale")) {
        throw Error(ErrorKind::BadInput, "give voxel_size or voxel_scale, not both", {"", 0, "voxel_scale"});
    }
    return out;
}

} // namespace strata::python
