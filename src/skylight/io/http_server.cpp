#include "skylight/io/http_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/io/file.h"

namespace skylight::io {
namespace {

std::string_view content_type(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".png") return "image/png";
  if (ext == ".json") return "application/json";
  return "application/octet-stream";
}

void send_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (n <= 0) return;  // the browser went away: nothing to answer
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

// The request line's path ("GET /index.html?x HTTP/1.1" -> "index.html"), or "" for anything else.
std::string requested_file(std::string_view request) {
  if (request.substr(0, 4) != "GET ") return {};
  std::string_view path = request.substr(4);
  path = path.substr(0, path.find_first_of(" ?#\r\n"));
  if (path.empty() || path.front() != '/') return {};
  path.remove_prefix(1);
  if (path.empty()) return "index.html";
  if (path.find('/') != std::string_view::npos || path.find("..") != std::string_view::npos ||
      path.find('%') != std::string_view::npos)
    return {};
  return std::string(path);
}

}  // namespace

StaticServer::StaticServer(std::filesystem::path folder, int port) : folder_(std::move(folder)) {
  socket_ = ::socket(AF_INET, SOCK_STREAM, 0);
  if (socket_ < 0) throw IoError("--serve: no socket: " + errno_message(errno));
  const int yes = 1;
  ::setsockopt(socket_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::bind(socket_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(socket_, 16) != 0) {
    const int err = errno;
    ::close(socket_);
    throw IoError(fmt::format("--serve {}: cannot listen on 127.0.0.1:{}: {}", port, port,
                              errno_message(err)));
  }
  socklen_t length = sizeof address;
  ::getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &length);
  port_ = ntohs(address.sin_port);
}

StaticServer::~StaticServer() {
  if (socket_ >= 0) ::close(socket_);
}

void StaticServer::serve(const std::function<bool()>& stop) const {
  constexpr int kPollMilliseconds = 250;
  while (!(stop && stop())) {
    pollfd p{socket_, POLLIN, 0};
    if (::poll(&p, 1, kPollMilliseconds) <= 0) continue;
    const int client = ::accept(socket_, nullptr, nullptr);
    if (client < 0) continue;
    std::string request(4096, '\0');
    const ssize_t n = ::recv(client, request.data(), request.size(), 0);
    request.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
    const std::string name = requested_file(request);
    const std::filesystem::path file = folder_ / name;
    std::error_code ec;
    if (!name.empty() && std::filesystem::is_regular_file(file, ec)) {
      const std::string body = read_text_file(file);
      send_all(client, fmt::format("HTTP/1.0 200 OK\r\nContent-Type: {}\r\nContent-Length: {}\r\n"
                                   "Cache-Control: no-store\r\nConnection: close\r\n\r\n",
                                   content_type(file), body.size()));
      send_all(client, body);
    } else {
      send_all(client,
               "HTTP/1.0 404 Not Found\r\nContent-Type: text/plain\r\nContent-Length: 10\r\n"
               "Connection: close\r\n\r\nnot found\n");
    }
    ::close(client);
  }
}

}  // namespace skylight::io
