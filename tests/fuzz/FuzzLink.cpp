// libFuzzer target: the robot link's decoders (core/link, docs/robot-link.md). The first byte
// chooses: 0 the binary request decoder on each request in turn (cut at its command's length), 1
// the JSON request decoder on the rest as one line, anything else the stream framer fed in chunks
// (sizes from the first byte) with each frame decoded and answered as the server would. The
// decoders never throw: any exception is a finding.
#include "core/link/LinkProtocol.h"
#include "core/link/RequestFramer.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

namespace {
using namespace scanpick::core::link;

void answer(const Decoded& d, bool binary) {
  Response r;
  r.command = d.request ? d.request->command : d.command;
  r.id = d.id;
  r.status = d.request ? Status::Ok : d.error;
  r.message = d.message;
  if (d.request)
    r.recipe = d.request->recipe; // echoed names may hold any bytes
  const std::string out = binary ? encodeBinaryResponse(r) : encodeJsonResponse(r);
  if (binary && !decodeBinaryResponse(out.substr(0, kBinaryResponseSize)))
    __builtin_trap(); // an answer the client cannot read
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const std::string_view rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  switch (data[0]) {
  case 0:
    // Each request as long as its command field says (a trigger at a flange pose is longer).
    for (std::size_t at = 0; at < rest.size();) {
      std::int32_t command = 0;
      if (rest.size() - at >= 8)
        std::memcpy(&command, rest.data() + at + 4, sizeof command);
      const std::size_t length = binaryRequestSize(command);
      answer(decodeBinaryRequest(rest.substr(at, length)), true);
      at += length;
    }
    break;
  case 1:
    answer(decodeJsonRequest(rest), false);
    break;
  default: {
    RequestFramer framer;
    const std::size_t chunk = std::size_t(data[0] % 37) + 1;
    for (std::size_t at = 0; at < rest.size(); at += chunk) {
      framer.feed(rest.substr(at, chunk));
      while (auto f = framer.next()) {
        if (f->kind == Frame::Kind::Binary)
          answer(decodeBinaryRequest(f->bytes), true);
        else if (f->kind == Frame::Kind::Json)
          answer(decodeJsonRequest(f->bytes), false);
      }
    }
    (void)framer.hasPartial();
    (void)framer.partialIsBinary();
  }
  }
  return 0;
}
