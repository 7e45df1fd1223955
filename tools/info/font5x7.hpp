#pragma once
// The 5x7 bitmap font of ffr-info's plots (font5x7.cpp): every printable ASCII character.
#include <array>
#include <cstdint>

namespace ffr::info {

/// Seven rows from the top, bit 4 = leftmost of the five columns.
using Glyph = std::array<std::uint8_t, 7>;

/// Glyphs of 0x20 (space) .. 0x7E (~), in order.
const std::array<Glyph, 95>& ascii_font();
/// The glyph of a byte; anything outside printable ASCII is a hollow box.
const Glyph& glyph(char c);

}  // namespace ffr::info
