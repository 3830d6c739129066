// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// A double as error messages print it (shortest stream form), shared by the
// nodes that check their options.

#include <strata/Format.h>

#include <string>

namespace strata::terrain::detail {

inline std::string show(double v) { return formatNumber(v); }

} // namespace strata::terrain::detail
