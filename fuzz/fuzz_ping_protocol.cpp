// libFuzzer harness: ping-protocol bytes → MessageParser, the payload parsers and Ping360Driver.
// The parser fed the input in random chunks must find the messages (and skipped runs) it finds in
// the whole input; each message must frame back to its own bytes; a payload that parses must write
// back the bytes it came from; the driver fed the same chunks must not throw. Byte 0 seeds the
// chunk sizes; the rest is the stream. A difference traps; any exception escapes as a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>
#include <vector>

#include "sonarmap/devices/ping360_driver.hpp"
#include "sonarmap/formats/ping_protocol.hpp"

namespace {

namespace pp = sonarmap::ping_protocol;

/// `Body` parsed from the message's payload must write the same payload back.
template <class Body>
void roundTrip(const pp::Message& message) {
  const std::optional<Body> body = Body::parse(message.payload);
  if (body && body->payload() != message.payload) std::abort();
}

void checkPayloads(const pp::Message& message) {
  roundTrip<pp::Ack>(message);
  roundTrip<pp::Nack>(message);
  roundTrip<pp::AsciiText>(message);
  roundTrip<pp::DeviceInformation>(message);
  roundTrip<pp::ProtocolVersion>(message);
  roundTrip<pp::GeneralRequest>(message);
  roundTrip<pp::SetDeviceId>(message);
  roundTrip<pp::DeviceData>(message);
  roundTrip<pp::AutoDeviceData>(message);
  roundTrip<pp::Reset>(message);
  roundTrip<pp::Transducer>(message);
  roundTrip<pp::AutoTransmit>(message);
  roundTrip<pp::MotorOff>(message);
  if (const std::optional<pp::DeviceData> ping = pp::DeviceData::parse(message.payload)) {
    pp::ping360Beam(*ping, 1500.0);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> stream(data + 1, size - 1);
  pp::MessageParser whole;
  const std::vector<pp::Message> expected = whole.feed(stream);
  for (const pp::Message& message : expected) {
    const std::vector<std::uint8_t> frame = pp::encode(message);
    if (pp::frameAt(frame).kind != pp::Framing::Kind::kMessage) std::abort();
    checkPayloads(message);
  }

  pp::MessageParser parser;
  sonarmap::Ping360Driver driver(sonarmap::HeadSettings{});
  driver.start(0.0);
  std::vector<pp::Message> found;
  std::uint32_t state = data[0] * 2654435761U + 1U;
  double now_s = 0.0;
  for (std::size_t at = 0; at < stream.size();) {
    state = state * 1664525U + 1013904223U;
    const std::size_t chunk = std::min<std::size_t>(stream.size() - at, 1 + (state >> 24) % 97);
    for (pp::Message& message : parser.feed(stream.subspan(at, chunk))) found.push_back(std::move(message));
    driver.receive(stream.subspan(at, chunk), now_s);
    now_s += 0.01 * static_cast<double>(state % 50);
    driver.poll(now_s);
    at += chunk;
  }
  driver.stop();
  if (found.size() != expected.size() || parser.skippedItems() != whole.skippedItems()) std::abort();
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (pp::encode(found[i]) != pp::encode(expected[i])) std::abort();
  }
  return 0;
}
