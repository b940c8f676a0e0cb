#pragma once
/// \file
/// The remote link's shared key (docs/remote.md, "Authentication"): with a key, every datagram
/// in both directions carries a 32-byte HMAC-SHA256 tag of its header and payload after the
/// payload (libsodium); a datagram whose tag is missing or wrong is dropped.

#include <s2sim/error.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace s2sim::links {

class DatagramKey {
 public:
  static constexpr std::size_t kTagSize = 32;
  static constexpr std::size_t kMinKeyBytes = 16;

  /// Reads the key from `path`: its bytes, less one trailing newline (a key file written by
  /// `head -c 32 /dev/urandom | base64 > key`, say). Throws s2sim::Error located at `where`
  /// when it cannot be read or holds fewer than kMinKeyBytes bytes.
  void load(const std::string& path, const Location& where);
  bool present() const { return !key_.empty(); }
  /// Bytes a datagram carries after its payload: kTagSize with a key, else 0.
  std::size_t tag_size() const { return present() ? kTagSize : 0; }

  /// Writes the tag of data[0, size) at data + size (room for kTagSize bytes).
  void seal(unsigned char* data, std::size_t size) const;
  /// Whether the last kTagSize bytes of data[0, size) are the tag of what precedes them
  /// (compared in constant time).
  bool verify(const unsigned char* data, std::size_t size) const;

 private:
  std::vector<unsigned char> key_;
};

}  // namespace s2sim::links
