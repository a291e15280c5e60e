// "Did you mean": the candidate nearest a word a user typed, by edit distance.
#pragma once

#include <string>
#include <vector>

namespace clpc {

// The candidate nearest `word`, if near enough to be a slip of the keyboard; else "".
std::string closest(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace clpc
