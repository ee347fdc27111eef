#include "viewer/PageServer.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "common/Error.h"

namespace baker {
namespace {

const std::map<std::string, std::string> kContentTypes = {
    {".html", "text/html; charset=utf-8"}, {".js", "text/javascript"}, {".json", "application/json"},
    {".gltf", "model/gltf+json"},           {".glb", "model/gltf-binary"}, {".png", "image/png"},
    {".jpg", "image/jpeg"},                 {".jpeg", "image/jpeg"}};

// The file a request path names inside `root`, or "" for anything outside it or not a file.
std::string fileFor(const std::filesystem::path& root, std::string path) {
  path = path.substr(0, path.find_first_of("?#"));
  if (path.empty() || path.back() == '/') path += "index.html";
  std::string decoded;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i] == '%' && i + 2 < path.size() && std::isxdigit(uint8_t(path[i + 1])) && std::isxdigit(uint8_t(path[i + 2]))) {
      decoded += char(std::stoi(path.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += path[i];
    }
  }
  const std::filesystem::path relative = std::filesystem::path(decoded).relative_path().lexically_normal();
  if (relative.empty() || *relative.begin() == "..") return "";
  std::error_code ec;
  const std::filesystem::path file = root / relative;
  return std::filesystem::is_regular_file(file, ec) ? file.string() : "";
}

void sendAll(int socket, const std::string& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(socket, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += std::size_t(n);
  }
}

void answer(int socket, const std::filesystem::path& root) {
  char buffer[8192];
  const ssize_t n = ::recv(socket, buffer, sizeof buffer - 1, 0);
  if (n <= 0) return;
  std::istringstream request(std::string(buffer, std::size_t(n)));
  std::string method, path;
  request >> method >> path;
  const std::string file = method == "GET" || method == "HEAD" ? fileFor(root, path) : "";
  if (file.empty()) {
    sendAll(socket, "HTTP/1.0 404 Not Found\r\nContent-Length: 0\r\nConnection: close\r\n\r\n");
    return;
  }
  std::ifstream in(file, std::ios::binary);
  const std::string body((std::istreambuf_iterator<char>(in)), {});
  const auto type = kContentTypes.find(std::filesystem::path(file).extension().string());
  sendAll(socket, fmt::format("HTTP/1.0 200 OK\r\nContent-Type: {}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                              type == kContentTypes.end() ? "application/octet-stream" : type->second, body.size()));
  if (method == "GET") sendAll(socket, body);
}

}  // namespace

void servePage(const std::string& directory, int port, const std::function<void(const std::string& url)>& listening) {
  const int server = ::socket(AF_INET, SOCK_STREAM, 0);
  if (server < 0) throw std::runtime_error(fmt::format("cannot open a socket: {}", std::strerror(errno)));
  const int yes = 1;
  ::setsockopt(server, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(std::uint16_t(port));
  if (::bind(server, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 || ::listen(server, 16) != 0) {
    const std::string why = std::strerror(errno);
    ::close(server);
    throw InputError(fmt::format("cannot serve on 127.0.0.1:{}: {}", port, why));
  }
  socklen_t length = sizeof address;
  ::getsockname(server, reinterpret_cast<sockaddr*>(&address), &length);
  listening(fmt::format("http://127.0.0.1:{}/", ntohs(address.sin_port)));
  const std::filesystem::path root = std::filesystem::absolute(directory);
  for (;;) {
    const int client = ::accept(server, nullptr, nullptr);
    if (client < 0) {
      if (errno == EINTR || errno == ECONNABORTED) continue;
      const std::string why = std::strerror(errno);
      ::close(server);
      throw std::runtime_error(fmt::format("serving {}: cannot accept a connection: {}", directory, why));
    }
    // One connection at a time: a client that sends or reads nothing must not stop the others.
    const timeval patience{5, 0};
    ::setsockopt(client, SOL_SOCKET, SO_RCVTIMEO, &patience, sizeof patience);
    ::setsockopt(client, SOL_SOCKET, SO_SNDTIMEO, &patience, sizeof patience);
    answer(client, root);
    ::close(client);
  }
  ::close(server);
}

}  // namespace baker
