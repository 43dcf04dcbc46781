#pragma once
// Text from input files shown in a message: a terminal acts on some bytes (ESC starts a control
// sequence that can move the cursor, recolour or retitle the window), so they are shown escaped,
// and a line may be megabytes long, so only its start is quoted.

#include <string>
#include <string_view>

namespace rgbdvo {

// s with every byte a terminal could act on written as \xNN: the ASCII control bytes (line
// ends and tabs too: a message is one line), DEL, the C1 controls (U+0080-U+009F in UTF-8) and
// any byte that is not part of a valid UTF-8 character. Everything else, other scripts
// included, is kept; a message already escaped is returned unchanged.
std::string Printable(std::string_view s);

// Printable(s) of at most the first max_bytes of s (cut where a UTF-8 character starts), with
// "..." after it when s is longer: a line of an input file quoted in a message.
std::string Excerpt(std::string_view s, size_t max_bytes = 80);

}  // namespace rgbdvo
