#pragma once
// Where `sonarmap live` reads a sonar's bytes from: a serial device (raw termios), a UDP port (bound,
// datagrams received), a TCP server (connected), standard input, or any readable file (a replay).
// POSIX only.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace sonarmap::cli {

/// An open byte source. Owns its file descriptor (not standard input's).
class LiveSource {
 public:
  /// Opens `spec`: "-" (standard input), "udp://HOST:PORT" (binds HOST:PORT; port 0 picks a free
  /// one, see description()), "tcp://HOST:PORT" (connects), else a path: a serial device is set
  /// raw (8N1, no flow control, no echo or line editing) at `baud` bits/s; another file is read as is.
  /// @throws ValueError for a malformed URL or a baud rate termios has no constant for;
  ///         FileError when the source cannot be opened, bound or connected (with the system's reason).
  LiveSource(const std::string& spec, unsigned baud);
  ~LiveSource();
  LiveSource(const LiveSource&) = delete;
  LiveSource& operator=(const LiveSource&) = delete;

  /// The file descriptor to poll for input.
  int fd() const { return fd_; }
  /// The source as opened, e.g. "udp://127.0.0.1:40123" (the port bound), "/dev/ttyUSB0 at 115200 baud".
  const std::string& description() const { return description_; }

  /// Reads what is available (one datagram for UDP) into `buffer`: the byte count, 0 at the end of
  /// the stream (end of file, connection closed, a serial line hung up), or -1 when interrupted or
  /// nothing was ready (try again).
  /// @throws FileError on a read error.
  long read(std::span<std::uint8_t> buffer);

 private:
  int fd_ = -1;
  bool owned_ = true;
  bool datagrams_ = false;
  std::string description_;
};

}  // namespace sonarmap::cli
