#pragma once
// Text from input files shown in a message: a terminal acts on some bytes (ESC starts a control
// sequence that can move the cursor, recolour or retitle the window), so they are shown escaped.

#include <string>
#include <string_view>

namespace rgbdvo {

// s with every byte a terminal could act on written as \xNN: the ASCII control bytes (line
// ends and tabs too: a message is one line), DEL, the C1 controls (U+0080-U+009F in UTF-8) and
// any byte that is not part of a valid UTF-8 character. Everything else, other scripts
// included, is kept; a message already escaped is returned unchanged.
std::string Printable(std::string_view s);

}  // namespace rgbdvo
