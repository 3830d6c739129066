#pragma once
// A double as error messages print it (shortest stream form), shared by the
// nodes that check their options.

#include <sstream>
#include <string>

namespace strata::terrain::detail {

inline std::string show(double v)
{
    std::ostringstream out;
    out << v;
    return out.str();
}

} // namespace strata::terrain::detail
