#include <strata/render/GlContext.h>

namespace strata::render {

GlContext::~GlContext() = default;

} // namespace strata::render
