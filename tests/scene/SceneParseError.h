// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The scene tests' helper: the message of the strata::Error that parsing a
// scene text throws (a test failure when it parses).

#include <strata/Error.h>
#include <strata/scene/Scene.h>

#include <gtest/gtest.h>

#include <string>

namespace strata::test {

inline std::string parseError(const std::string& text)
{
    try {
        strata::scene::parseScene(text, "test.toml");
    } catch (const strata::Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return {};
}

} // namespace strata::test
