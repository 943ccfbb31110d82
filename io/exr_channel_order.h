// The order OpenImageIO 2.4 presents an EXR's channels in (inside io/ only): by layer (the
// name before the last '.'), then R, G, B, A, ... before the other names, so that ssrt's own
// EXR reader and OpenImageIO give a comparison or a channel list the same order.
#pragma once

#include <string>
#include <vector>

namespace ssrt::io_detail {

// `names` (in the file's order) in OpenImageIO's.
std::vector<std::string> exrChannelOrder(const std::vector<std::string>& names);

}  // namespace ssrt::io_detail
