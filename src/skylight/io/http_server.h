// A static file server on the loopback interface (`skylight view --serve`, docs/VIEWER.md): the
// files of one folder over HTTP/1.0 GET, for browsers that restrict pages opened from file://.
// One request at a time, no subfolders, nothing outside the folder.
#pragma once

#include <filesystem>
#include <functional>

namespace skylight::io {

class StaticServer {
 public:
  // Listens on 127.0.0.1:port (0: a free port the system picks). Throws IoError naming the port
  // when it cannot (in use, not allowed).
  StaticServer(std::filesystem::path folder, int port);
  ~StaticServer();
  StaticServer(const StaticServer&) = delete;
  StaticServer& operator=(const StaticServer&) = delete;
  int port() const { return port_; }
  // Answers requests until `stop` returns true (asked between requests and every 0.25 s; empty:
  // until the process is interrupted). "/" is index.html; a path with a '/' inside, "..", or a
  // file that is not in the folder is 404.
  void serve(const std::function<bool()>& stop) const;

 private:
  std::filesystem::path folder_;
  int socket_ = -1;
  int port_ = 0;
};

}  // namespace skylight::io
