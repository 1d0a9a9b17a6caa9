/// @file byte_link.cpp
/// Serial devices, UDP, TCP, pseudo-terminals and files as byte links (see byte_link.hpp).

#include "sonarmap/live/byte_link.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <utility>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

static_assert(sizeof(sockaddr_storage) <= 128, "ByteLink keeps a peer's address in 128 bytes");

std::string systemError() { return std::strerror(errno); }

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// The termios constant of `baud` bits/s. @throws ValueError when there is none.
speed_t baudConstant(unsigned baud) {
  static const std::pair<unsigned, speed_t> kSpeeds[] = {
      {1200, B1200},     {2400, B2400},     {4800, B4800},     {9600, B9600},     {19200, B19200},
      {38400, B38400},   {57600, B57600},   {115200, B115200}, {230400, B230400}, {460800, B460800},
      {500000, B500000}, {921600, B921600}, {1000000, B1000000}, {2000000, B2000000}, {3000000, B3000000}};
  for (const auto& [rate, constant] : kSpeeds) {
    if (rate == baud) return constant;
  }
  throw ValueError("--baud " + std::to_string(baud) +
                   " is not a standard rate (1200, 2400, ..., 115200, 230400, 460800, 500000, 921600, 1000000, "
                   "2000000, 3000000)");
}

/// Sets `fd`, a terminal, raw: 8 bits, no parity, one stop bit, no flow control, no echo, no line
/// editing, no CR/LF translation, reads returning as soon as a byte is there.
/// @return false (errno set) when termios refuses.
bool setRaw(int fd, speed_t speed) {
  termios settings{};
  if (::tcgetattr(fd, &settings) != 0) return false;
  ::cfmakeraw(&settings);
  settings.c_cflag |= CLOCAL | CREAD;
  settings.c_cflag &= ~(CSTOPB | CRTSCTS);
  settings.c_cc[VMIN] = 1;
  settings.c_cc[VTIME] = 0;
  return ::cfsetispeed(&settings, speed) == 0 && ::cfsetospeed(&settings, speed) == 0 &&
         ::tcsetattr(fd, TCSANOW, &settings) == 0;
}

/// "HOST:PORT" of a URL after its scheme. @throws ValueError when the port is missing.
std::pair<std::string, std::string> hostAndPort(const std::string& spec, std::size_t scheme_bytes) {
  const std::string rest = spec.substr(scheme_bytes);
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon + 1 == rest.size()) {
    throw ValueError("'" + spec + "': expected " + spec.substr(0, scheme_bytes) + "HOST:PORT or " +
                     spec.substr(0, scheme_bytes) + ":PORT");
  }
  std::string host = rest.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  return {host, rest.substr(colon + 1)};
}

bool isWildcard(const std::string& host) { return host.empty() || host == "0.0.0.0" || host == "::"; }

/// "HOST:PORT" of a socket address, numeric.
std::string addressText(const sockaddr* address, socklen_t size) {
  char host[NI_MAXHOST];
  char port[NI_MAXSERV];
  if (::getnameinfo(address, size, host, sizeof host, port, sizeof port, NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    return "?";
  }
  const std::string text(host);
  return (text.find(':') != std::string::npos ? "[" + text + "]" : text) + ":" + port;
}

}  // namespace

ByteLink::ByteLink(const std::string& spec, unsigned baud) {
  if (spec == "-") {
    fd_ = STDIN_FILENO;
    owned_ = false;
    description_ = "standard input";
    return;
  }
  if (spec.starts_with("udp://") || spec.starts_with("tcp://")) {
    openSocket(spec, spec.starts_with("udp://"));
    return;
  }
  if (spec.starts_with("pty:")) {
    pty_link_ = spec.substr(4);
    if (pty_link_.empty()) throw ValueError("'" + spec + "': expected pty:PATH, the path to link to the terminal");
    fd_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0 || ::grantpt(fd_) != 0 || ::unlockpt(fd_) != 0) {
      throw FileError("'" + spec + "': cannot open a pseudo-terminal: " + systemError());
    }
    const char* slave_name = ::ptsname(fd_);
    if (slave_name == nullptr) throw FileError("'" + spec + "': no name for the pseudo-terminal: " + systemError());
    const std::string slave(slave_name);
    pty_slave_fd_ = ::open(slave.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (pty_slave_fd_ < 0 || !setRaw(pty_slave_fd_, B115200)) {
      throw FileError("'" + spec + "': cannot set " + slave + " raw: " + systemError());
    }
    std::error_code error;
    std::filesystem::remove(pty_link_, error);
    std::filesystem::create_symlink(slave, pty_link_, error);
    if (error) {
      const std::string why = error.message();
      pty_link_.clear();
      throw FileError("'" + spec + "': cannot link it to " + slave + ": " + why);
    }
    writable_ = true;
    description_ = "pty " + pty_link_ + " (" + slave + ")";
    return;
  }
  const speed_t speed = baudConstant(baud);
  fd_ = ::open(spec.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (fd_ < 0 && (errno == EACCES || errno == EROFS || errno == EISDIR)) {
    fd_ = ::open(spec.c_str(), O_RDONLY | O_NOCTTY | O_CLOEXEC);
  }
  if (fd_ < 0) throw FileError("cannot open '" + spec + "': " + systemError());
  description_ = spec;
  if (::isatty(fd_) == 0) return;  // a file or a FIFO: read as it is
  if (!setRaw(fd_, speed)) {
    throw FileError("'" + spec + "': cannot set it raw at " + std::to_string(baud) + " baud: " + systemError());
  }
  writable_ = true;
  description_ = spec + " at " + std::to_string(baud) + " baud";
}

void ByteLink::openSocket(const std::string& spec, bool udp) {
  const auto [host, port] = hostAndPort(spec, 6);
  datagrams_ = udp;
  listening_ = isWildcard(host);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = udp ? SOCK_DGRAM : SOCK_STREAM;
  hints.ai_flags = listening_ ? AI_PASSIVE : 0;
  addrinfo* found = nullptr;
  // A listener on any address takes IPv4 and IPv6 peers alike through an IPv6 socket when there is one.
  const char* node = listening_ ? (host == "0.0.0.0" ? "0.0.0.0" : nullptr) : host.c_str();
  if (const int error = ::getaddrinfo(node, port.c_str(), &hints, &found); error != 0) {
    throw FileError("'" + spec + "': " + ::gai_strerror(error));
  }
  std::string why = "no address";
  int fd = -1;
  for (const addrinfo* address = found; address != nullptr && fd < 0; address = address->ai_next) {
    fd = ::socket(address->ai_family, address->ai_socktype | SOCK_CLOEXEC, address->ai_protocol);
    if (fd < 0) {
      why = systemError();
      continue;
    }
    if (udp) {
      // A sonar's datagrams come in bursts and nothing resends a lost one: room for seconds of them
      // while a sweep is detected or the map written (SO_RCVBUFFORCE passes net.core.rmem_max when
      // privileged; else the request is capped there).
      constexpr int kReceiveBuffer = 8 << 20;
      if (::setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &kReceiveBuffer, sizeof kReceiveBuffer) != 0) {
        ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &kReceiveBuffer, sizeof kReceiveBuffer);
      }
    }
    if (listening_) {
      const int yes = 1;
      ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
      if (address->ai_family == AF_INET6) {
        const int no = 0;
        ::setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &no, sizeof no);
      }
    }
    const int done = listening_ ? ::bind(fd, address->ai_addr, address->ai_addrlen)
                                : ::connect(fd, address->ai_addr, address->ai_addrlen);
    if (done != 0 || (listening_ && !udp && ::listen(fd, 1) != 0)) {
      why = systemError();
      ::close(fd);
      fd = -1;
    }
  }
  ::freeaddrinfo(found);
  if (fd < 0) throw FileError("'" + spec + "': cannot " + (listening_ ? "bind: " : "connect: ") + why);
  sockaddr_storage bound{};
  socklen_t size = sizeof bound;
  const std::string scheme = udp ? "udp://" : "tcp://";
  description_ = spec;
  if (listening_ && ::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &size) == 0) {
    // name the port bound (port 0: the system's choice)
    std::string text = addressText(reinterpret_cast<sockaddr*>(&bound), size);
    if (text.starts_with("[::]:")) text = text.substr(4);
    if (text.starts_with("0.0.0.0:")) text = text.substr(7);
    description_ = scheme + text;
  }
  if (!udp && listening_) {
    listen_fd_ = fd;
    fd_ = fd;
  } else {
    fd_ = fd;
  }
  socket_ = true;
  writable_ = true;
}

ByteLink::~ByteLink() {
  if (owned_ && fd_ >= 0) ::close(fd_);
  if (listen_fd_ >= 0 && listen_fd_ != fd_) ::close(listen_fd_);
  if (pty_slave_fd_ >= 0) ::close(pty_slave_fd_);
  if (!pty_link_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(pty_link_, ignored);
  }
}

void ByteLink::notePeer(const void* address, unsigned length) {
  const double now_s = steadySeconds();
  for (Peer& peer : peers_) {
    if (peer.length == length && std::memcmp(peer.address, address, length) == 0) {
      peer.heard_s = now_s;
      return;
    }
  }
  Peer peer;
  std::memcpy(peer.address, address, length);
  peer.length = length;
  peer.heard_s = now_s;
  peers_.push_back(peer);
  forgetSilentPeers();
}

void ByteLink::forgetSilentPeers() {
  const double now_s = steadySeconds();
  std::erase_if(peers_, [&](const Peer& peer) { return now_s - peer.heard_s > kUdpPeerTimeout_s; });
  if (peers_.size() <= kUdpMaxPeers) return;
  std::stable_sort(peers_.begin(), peers_.end(), [](const Peer& a, const Peer& b) { return a.heard_s > b.heard_s; });
  peers_.resize(kUdpMaxPeers);
}

long ByteLink::acceptClient() {
  const int client = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
  if (client < 0) {
    if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK || errno == ECONNABORTED) return -1;
    throw FileError("accepting a client on " + description_ + ": " + systemError());
  }
  fd_ = client;
  return -1;
}

long ByteLink::read(std::span<std::uint8_t> buffer) {
  if (listen_fd_ >= 0 && fd_ == listen_fd_) return acceptClient();
  ssize_t got = 0;
  if (datagrams_ && listening_) {
    sockaddr_storage from{};
    socklen_t size = sizeof from;
    got = ::recvfrom(fd_, buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&from), &size);
    if (got > 0) notePeer(&from, size);  // an empty datagram registers no one (bridges: a line break)
  } else if (datagrams_) {
    got = ::recv(fd_, buffer.data(), buffer.size(), 0);
  } else {
    got = ::read(fd_, buffer.data(), buffer.size());
  }
  if (got > 0) return static_cast<long>(got);
  if (got == 0) {
    if (datagrams_) return -1;  // an empty datagram
    if (listen_fd_ >= 0) {      // the client left: wait for the next one
      ::close(fd_);
      fd_ = listen_fd_;
      return -1;
    }
    return 0;
  }
  if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK) return -1;
  // A connected UDP socket whose peer is not listening (yet): the ICMP error surfaces here; the
  // next datagram sent may find it.
  if (datagrams_ && errno == ECONNREFUSED) return -1;
  if (errno == EIO) return 0;  // a serial line (or pseudo-terminal) whose other end hung up
  if (listen_fd_ >= 0 && (errno == ECONNRESET || errno == EPIPE)) {
    ::close(fd_);
    fd_ = listen_fd_;
    return -1;
  }
  throw FileError("reading " + description_ + ": " + systemError());
}

bool ByteLink::write(std::span<const std::uint8_t> bytes) {
  if (!writable_) throw FileError(description_ + " cannot be written to: a head needs a serial device, udp:// or tcp://");
  if (bytes.empty()) return true;
  if (datagrams_) {
    ssize_t sent = 0;
    if (listening_) {
      forgetSilentPeers();
      bool reached = false;
      for (const Peer& peer : peers_) {
        if (::sendto(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL, reinterpret_cast<const sockaddr*>(peer.address),
                     peer.length) >= 0) {
          reached = true;
        } else if (errno != ECONNREFUSED && errno != EINTR && errno != EAGAIN) {
          throw FileError("sending to a peer of " + description_ + ": " + systemError());
        }
      }
      return reached;
    } else {
      sent = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    }
    if (sent < 0) {
      if (errno == ECONNREFUSED || errno == EINTR || errno == EAGAIN) return false;  // the peer is not there yet
      throw FileError("sending to " + description_ + ": " + systemError());
    }
    return true;
  }
  if (listen_fd_ >= 0 && fd_ == listen_fd_) return false;  // no client yet
  std::size_t done = 0;
  while (done < bytes.size()) {
    // send() on a TCP socket (no SIGPIPE when the peer is gone), write() on a terminal
    const ssize_t wrote = socket_ ? ::send(fd_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL)
                                  : ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (wrote >= 0) {
      done += static_cast<std::size_t>(wrote);
      continue;
    }
    if (errno == EINTR || errno == EAGAIN) continue;
    if (listen_fd_ >= 0 && (errno == EPIPE || errno == ECONNRESET)) {
      ::close(fd_);
      fd_ = listen_fd_;
      return false;
    }
    throw FileError("writing to " + description_ + ": " + systemError());
  }
  return true;
}

}  // namespace sonarmap
