// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The EGL context of the GL tests: a test fails (never skips) without one,
// since CI has EGL on llvmpipe.

#include <strata/Error.h>
#include <strata/render/EglContext.h>

#include <gtest/gtest.h>

#include <memory>

namespace strata::test {

/// A new EGL context, or null after recording a test failure with the reason.
inline std::unique_ptr<render::EglContext> createContext()
{
    try {
        return render::EglContext::create();
    } catch (const strata::Error& e) {
        ADD_FAILURE() << "no EGL context: " << e.what();
        return nullptr;
    }
}

} // namespace strata::test
