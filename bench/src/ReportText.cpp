// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/bench/ReportText.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include <cmath>
#include <cstdio>
#include <fstream>

namespace strata::bench {

std::string fixedOrBlank(double value, int digits)
{
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    if (std::isnan(value)) return "";
    return fixedDigits(value, digits);
}

std::string fixedDigits(double value, int digits)
{
    char text[64];
    std::snprintf(text, sizeof(text), "%.*f", digits, value);
    return text;
}

void writeTextFile(const std::filesystem::path& path, const std::string& text)
{
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out << text;
        if (!out.flush()) throw Error(ErrorKind::Io, "cannot write '" + path.string() + "'", {path.string()});
    });
}

} // namespace strata::bench
