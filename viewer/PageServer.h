#pragma once
#include <functional>
#include <string>

namespace baker {

// Serves the files of `directory` over HTTP on 127.0.0.1 only (GET and HEAD, one request per
// connection), for a page that a browser will not load from file:// (module scripts and fetch
// need an origin). port 0 takes a free one. Calls `listening` with the address once it accepts
// connections, then serves until the process is interrupted. InputError when the port is taken.
void servePage(const std::string& directory, int port, const std::function<void(const std::string& url)>& listening);

}  // namespace baker
