// Text helpers every layer uses for messages: numbers as their shortest round-trip text, ASCII
// upper case, text made safe inside XML and HTML.
#pragma once

#include <string>
#include <string_view>

namespace clpc {

// Shortest round-trip text of a number, for messages and the IR printer ("0", "12", "0.004").
std::string num_text(double v);
// A number with a fixed count of decimals, for reports and messages ("0.00040").
std::string fixed_text(double v, int decimals);
std::string upper(std::string_view s);  // ASCII upper case
// Text for an XML or HTML page (the backplot, the verify report): < > & " escaped, control
// characters dropped.
std::string xml_text(std::string_view s);
// `s` as a JSON string, quoted: " and \ escaped, control characters as \u00XX.
std::string json_text(std::string_view s);

}  // namespace clpc
