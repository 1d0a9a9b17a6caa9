#pragma once
/// @file byte_link.hpp
/// The byte links a sonar head, an autopilot's navigation and an emulated head talk over: a serial
/// device, UDP, TCP, a pseudo-terminal, standard input or a recorded file. POSIX only.
///
/// Specifications, as `sonarmap live` and `sonarmap emulate` take them:
///  - "udp://HOST:PORT": sends to HOST:PORT and reads the replies (a Ping360 over Ethernet, BlueOS's
///    ping proxy on port 9092, MAVProxy's `udpout`); the peer answers the port this end was given.
///  - "udp://:PORT" (or a wildcard host, 0.0.0.0 or [::]): listens on PORT (ArduSub's MAVLink
///    stream to port 14550, MAVProxy's `udpin`). Writes go to every peer a datagram came from in
///    the last kUdpPeerTimeout_s, the kUdpMaxPeers most recent, as BlueOS's `bridges` serves a
///    serial head's bytes to its UDP clients (patrickelectric/bridges, src/socket.rs: clients kept
///    10 s after their last datagram, 5 at most, newest kept) and as BlueOS's MAVLink "UDP Server"
///    endpoints answer the clients that have spoken.
///  - "tcp://HOST:PORT": connects; "tcp://:PORT" listens and takes one client at a time.
///  - "pty:PATH" (emulators): opens a pseudo-terminal and links PATH to it, so a program opens PATH
///    as the serial device of a head.
///  - "-": standard input (read only).
///  - any other path: a serial device (set raw, 8N1, no flow control, at the given baud rate), or
///    a file or FIFO read as it is (read only).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sonarmap {

/// An open link. Owns its file descriptors (not standard input's) and removes a pty's link.
class ByteLink {
 public:
  /// A listening UDP link forgets a peer this long after its last datagram (seconds; bridges' 10 s).
  static constexpr double kUdpPeerTimeout_s = 10.0;
  /// A listening UDP link serves at most this many peers, the most recently heard (bridges' default 5).
  static constexpr std::size_t kUdpMaxPeers = 5;

  /// Opens `spec` (see the file's comment); `baud` is used for serial devices only.
  /// @throws ValueError for a malformed URL or a baud rate termios has no constant for;
  ///         FileError when the link cannot be opened, bound, connected or linked (with the
  ///         system's reason).
  ByteLink(const std::string& spec, unsigned baud);
  ~ByteLink();
  ByteLink(const ByteLink&) = delete;
  ByteLink& operator=(const ByteLink&) = delete;

  /// The file descriptor to poll for input (a listening TCP link's: until a client connects, its
  /// readiness means a client is waiting, which read() accepts).
  int fd() const { return fd_; }
  /// The link as opened: "udp://127.0.0.1:40123" (the port bound), "/dev/ttyUSB0 at 115200 baud",
  /// "pty /tmp/ping360 (/dev/pts/3)".
  const std::string& description() const { return description_; }
  /// Whether write() can reach a peer at all (false for standard input and files).
  bool writable() const { return writable_; }
  /// Whether this end can speak first: a serial device, a pseudo-terminal, or a UDP or TCP link to
  /// a HOST:PORT (false for a listening link, which answers the peers that spoke, standard input and
  /// files). A head is driven only over such a link: a Ping360 or a SeaNet head never speaks first.
  bool speaksFirst() const { return writable_ && !listening_; }
  /// Whether this is a serial device or a pseudo-terminal (bytes take their time at a baud rate).
  bool serial() const { return writable_ && !socket_; }
  /// Whether this is a UDP or TCP link to a HOST:PORT: a server there (BlueOS's endpoints and
  /// bridges) sends only to clients it has heard from.
  bool networkClient() const { return socket_ && !listening_; }

  /// Reads what is available (one datagram for UDP) into `buffer`: the byte count; 0 at the end of
  /// the stream (end of file, the TCP peer gone, a serial line hung up); -1 when interrupted or
  /// nothing was ready, or a listening TCP link accepted a client (try again).
  /// @throws FileError on a read error.
  long read(std::span<std::uint8_t> buffer);
  /// Writes `bytes` whole (one datagram for UDP, to each peer of a listening link). Returns false,
  /// writing nothing, when there is no peer (a listening link that heard no one in the last
  /// kUdpPeerTimeout_s, a TCP listener without a client).
  /// @throws FileError on a write error, or on a link that is not writable.
  bool write(std::span<const std::uint8_t> bytes);

 private:
  void openSocket(const std::string& spec, bool udp);
  long acceptClient();
  /// A datagram came from `address` (a sockaddr of `length` bytes): that peer is heard now.
  void notePeer(const void* address, unsigned length);
  /// Drops the peers silent for longer than kUdpPeerTimeout_s, and all but the kUdpMaxPeers newest.
  void forgetSilentPeers();

  int fd_ = -1;
  int listen_fd_ = -1;     ///< a listening TCP link's socket (fd_ is then its client, or listen_fd_)
  int pty_slave_fd_ = -1;  ///< a pty's slave end, held open so the master never sees a hang-up
  bool owned_ = true;
  bool socket_ = false;
  bool datagrams_ = false;
  bool listening_ = false;  ///< UDP: writes go to the peers heard; TCP: accepts clients
  bool writable_ = false;
  std::string pty_link_;   ///< the path linked to the pty, removed on close
  std::string description_;
  /// A listening UDP link's peers: each address (a sockaddr_storage's bytes, its length) and when
  /// its last datagram came (steady clock, seconds).
  struct Peer {
    alignas(8) std::uint8_t address[128] = {};
    unsigned length = 0;
    double heard_s = 0.0;
  };
  std::vector<Peer> peers_;
};

}  // namespace sonarmap
