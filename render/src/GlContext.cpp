// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/GlContext.h>

namespace strata::render {

GlContext::~GlContext() = default;

} // namespace strata::render
