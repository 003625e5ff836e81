// Typo suggestions for names a user types (flags, subcommands, models, cameras).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace skylight {

// Edit distance (optimal string alignment): the fewest single-character insertions, deletions,
// substitutions and swaps of two adjacent characters that turn a into b (case-sensitive, bytes).
std::size_t edit_distance(std::string_view a, std::string_view b);

// Names shorter than this (leading dashes not counted) get no suggestion: one edit away from a
// two-letter name is any other two-letter name.
inline constexpr std::size_t kMinSuggestedLength = 3;

// The candidate nearest to `typed` when it is near enough to be a typo of it: at most
// max(1, n / 3) edits for a name of n characters after its leading dashes (so "--turbidty" ->
// "--turbidity", "trian" -> "train", but no suggestion for a different word). Ties go to the
// first candidate. nullopt when none is near.
std::optional<std::string> nearest_name(std::string_view typed,
                                        std::span<const std::string> candidates);

// "; did you mean 'X'?" for the nearest candidate, or "" when none is near.
std::string did_you_mean(std::string_view typed, std::span<const std::string> candidates);

}  // namespace skylight
