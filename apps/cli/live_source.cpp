#include "live_source.hpp"

#include <cerrno>
#include <cstring>
#include <utility>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {
namespace {

std::string systemError() { return std::strerror(errno); }

/// The termios constant of `baud` bits/s. @throws ValueError when there is none.
speed_t baudConstant(unsigned baud) {
  static const std::pair<unsigned, speed_t> kSpeeds[] = {
      {1200, B1200},     {2400, B2400},     {4800, B4800},     {9600, B9600},     {19200, B19200},
      {38400, B38400},   {57600, B57600},   {115200, B115200}, {230400, B230400}, {460800, B460800},
      {500000, B500000}, {921600, B921600}, {1000000, B1000000}};
  for (const auto& [rate, constant] : kSpeeds) {
    if (rate == baud) return constant;
  }
  throw ValueError("--baud " + std::to_string(baud) +
                   " is not a standard rate (1200, 2400, ..., 115200, 230400, 460800, 500000, 921600, 1000000)");
}

/// "HOST:PORT" of a URL after its scheme. @throws ValueError when the port is missing.
std::pair<std::string, std::string> hostAndPort(const std::string& spec, std::size_t scheme_bytes) {
  const std::string rest = spec.substr(scheme_bytes);
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == rest.size()) {
    throw ValueError("'" + spec + "': expected " + spec.substr(0, scheme_bytes) + "HOST:PORT");
  }
  std::string host = rest.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  return {host, rest.substr(colon + 1)};
}

/// A socket bound (UDP) or connected (TCP) to `spec`'s address. @throws FileError on failure.
int openSocket(const std::string& spec, bool udp, std::string& description) {
  const auto [host, port] = hostAndPort(spec, 6);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = udp ? SOCK_DGRAM : SOCK_STREAM;
  hints.ai_flags = udp ? AI_PASSIVE : 0;
  addrinfo* found = nullptr;
  if (const int error = ::getaddrinfo(host.c_str(), port.c_str(), &hints, &found); error != 0) {
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
    const int done = udp ? ::bind(fd, address->ai_addr, address->ai_addrlen) : ::connect(fd, address->ai_addr, address->ai_addrlen);
    if (done != 0) {
      why = systemError();
      ::close(fd);
      fd = -1;
    }
  }
  ::freeaddrinfo(found);
  if (fd < 0) throw FileError("'" + spec + "': cannot " + (udp ? "bind: " : "connect: ") + why);
  description = spec;
  if (udp) {  // name the port bound (port 0: the system's choice)
    sockaddr_storage bound{};
    socklen_t size = sizeof bound;
    char numeric_host[NI_MAXHOST];
    char numeric_port[NI_MAXSERV];
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &size) == 0 &&
        ::getnameinfo(reinterpret_cast<sockaddr*>(&bound), size, numeric_host, sizeof numeric_host, numeric_port,
                      sizeof numeric_port, NI_NUMERICHOST | NI_NUMERICSERV) == 0) {
      description = "udp://" + std::string(numeric_host) + ":" + numeric_port;
    }
  }
  return fd;
}

}  // namespace

LiveSource::LiveSource(const std::string& spec, unsigned baud) {
  if (spec == "-") {
    fd_ = STDIN_FILENO;
    owned_ = false;
    description_ = "standard input";
    return;
  }
  if (spec.starts_with("udp://") || spec.starts_with("tcp://")) {
    datagrams_ = spec.starts_with("udp://");
    fd_ = openSocket(spec, datagrams_, description_);
    return;
  }
  const speed_t speed = baudConstant(baud);
  fd_ = ::open(spec.c_str(), O_RDONLY | O_NOCTTY | O_CLOEXEC);
  if (fd_ < 0) throw FileError("cannot open '" + spec + "' for reading: " + systemError());
  description_ = spec;
  if (::isatty(fd_) == 0) return;  // a file or a FIFO: read as is
  termios settings{};
  if (::tcgetattr(fd_, &settings) != 0) throw FileError("'" + spec + "': cannot read its serial settings: " + systemError());
  ::cfmakeraw(&settings);  // 8 bits, no parity, no echo, no line editing, no CR/LF translation
  settings.c_cflag |= CLOCAL | CREAD;
  settings.c_cflag &= ~(CSTOPB | CRTSCTS);
  settings.c_cc[VMIN] = 1;
  settings.c_cc[VTIME] = 0;
  if (::cfsetispeed(&settings, speed) != 0 || ::cfsetospeed(&settings, speed) != 0 ||
      ::tcsetattr(fd_, TCSANOW, &settings) != 0) {
    throw FileError("'" + spec + "': cannot set it raw at " + std::to_string(baud) + " baud: " + systemError());
  }
  description_ = spec + " at " + std::to_string(baud) + " baud";
}

LiveSource::~LiveSource() {
  if (owned_ && fd_ >= 0) ::close(fd_);
}

long LiveSource::read(std::span<std::uint8_t> buffer) {
  const ssize_t got = datagrams_ ? ::recv(fd_, buffer.data(), buffer.size(), 0) : ::read(fd_, buffer.data(), buffer.size());
  if (got >= 0) return static_cast<long>(got);
  if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK) return -1;
  if (errno == EIO) return 0;  // a serial line (or pseudo-terminal) whose other end hung up
  throw FileError("reading " + description_ + ": " + systemError());
}

}  // namespace sonarmap::cli
