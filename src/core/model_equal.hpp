// Exact equality of two models, field by field (internal).
//
// The C-space builder keeps a copy of the model in every space it builds (contact geometry
// queries read it). A space built on the same thread while an equal copy is still held by a
// live space shares that copy instead of making another (cspace/builder_model.cpp): this is
// the test that decides "equal". Every field of every model type is compared (rationals
// exactly, strings byte for byte); src/core/model_equal.cpp checks the size of each type at
// compile time, so that a field added to a model type fails the build until it is compared.
#pragma once

#include <hipair/model.hpp>

namespace hipair {

/// True when every field of `a` equals the same field of `b` (exact rationals, strings, flags,
/// indices, optional and nested values).
bool same_model(const Model& a, const Model& b);

}  // namespace hipair
