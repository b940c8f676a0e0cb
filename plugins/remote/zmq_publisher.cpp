#include "zmq_publisher.hpp"

#ifdef S2SIM_HAVE_ZMQ
#include <zmq.h>
#endif

namespace s2sim::links {

#ifdef S2SIM_HAVE_ZMQ

ZmqPublisher::ZmqPublisher(const std::string& endpoint, int high_water_mark,
                           const Location& where) {
  context_ = zmq_ctx_new();
  socket_ = context_ ? zmq_socket(context_, ZMQ_PUB) : nullptr;
  if (!socket_) {
    if (context_) zmq_ctx_term(context_);
    throw Error(ErrorKind::plugin, where,
                std::string("cannot open a ZeroMQ PUB socket: ") + zmq_strerror(zmq_errno()));
  }
  const int linger_ms = 0;  // closing never waits for a subscriber
  zmq_setsockopt(socket_, ZMQ_LINGER, &linger_ms, sizeof linger_ms);
  zmq_setsockopt(socket_, ZMQ_SNDHWM, &high_water_mark, sizeof high_water_mark);
  if (zmq_bind(socket_, endpoint.c_str()) != 0) {
    const std::string why = zmq_strerror(zmq_errno());
    zmq_close(socket_);
    zmq_ctx_term(context_);
    throw Error(ErrorKind::scene, where, "cannot bind ZeroMQ '" + endpoint + "': " + why);
  }
  char bound[256] = {};
  std::size_t len = sizeof bound;
  zmq_getsockopt(socket_, ZMQ_LAST_ENDPOINT, bound, &len);
  bound_ = bound;
  const std::size_t colon = bound_.rfind(':');
  if (bound_.rfind("tcp://", 0) == 0 && colon != std::string::npos)
    port_ = std::stoi(bound_.substr(colon + 1));
}

ZmqPublisher::~ZmqPublisher() {
  zmq_close(socket_);
  zmq_ctx_term(context_);
}

bool ZmqPublisher::send(const std::uint8_t* data, std::size_t size) {
  return zmq_send(socket_, data, size, ZMQ_DONTWAIT) == static_cast<int>(size);
}

#else

ZmqPublisher::ZmqPublisher(const std::string&, int, const Location& where) {
  throw Error(ErrorKind::scene, where,
              "this S2Sim was built without ZeroMQ (install libzmq3-dev: "
              "scripts/install-deps.sh, and build again)");
}
ZmqPublisher::~ZmqPublisher() = default;
bool ZmqPublisher::send(const std::uint8_t*, std::size_t) {
  return false;
}

#endif

}  // namespace s2sim::links
