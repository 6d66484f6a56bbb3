// A binary archive of a run's changing state, for checkpoints (run/checkpoint.hpp). One
// function per class lists what changes (`template <class Ar> void persist(Ar& ar)`), and the
// same list both saves and loads, so the two cannot drift apart. Values are stored as their
// bytes (a checkpoint is read back by the same build on the same machine type; the file's
// header refuses another build). Loading checks every length against what is left, so a
// truncated or corrupt file is an Error, never a read past the end or a huge allocation.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace dspdem {

class StateArchive {
 public:
  /// An empty archive to save into.
  StateArchive() = default;
  /// An archive that loads from bytes (source names them in messages).
  StateArchive(std::string bytes, std::string source)
      : loading_(true), bytes_(std::move(bytes)), source_(std::move(source)) {}

  bool loading() const { return loading_; }
  const std::string& bytes() const { return bytes_; }
  /// Bytes not yet read (loading).
  std::size_t remaining() const { return bytes_.size() - pos_; }

  template <class T>
  StateArchive& operator()(T& v) {
    io(v);
    return *this;
  }
  template <class T, class... Rest>
  StateArchive& operator()(T& v, Rest&... rest) {
    io(v);
    return (*this)(rest...);
  }

  /// Parts of the model (walls, bodies) that the model built from the case has already: only
  /// their state is stored, and a load into a model with another count is refused.
  template <class V>
  void parts(V& v, const char* what) {
    std::uint64_t n = v.size();
    raw(&n, sizeof n);
    DSPDEM_CHECK(n == v.size(), "checkpoint '{}': {} {} stored, the model has {} (another model)", source_, n, what,
                 v.size());
    for (auto& e : v) io(e);
  }

  /// A label between sections: a checkpoint whose sections do not line up (another model,
  /// a bug) stops at the first label that differs instead of loading shifted bytes.
  void section(const char* name) {
    std::string s(name);
    if (!loading_) return io(s);
    std::string got;
    io(got);
    DSPDEM_CHECK(got == s,
                 "checkpoint '{}': expected section '{}' at byte {}, found '{}' (corrupt file or another model)",
                 source_, s, pos_, got.substr(0, 40));
  }

 private:
  template <class T>
  void io(T& v) {
    if constexpr (std::is_same_v<T, std::string>) {
      std::uint64_t n = v.size();
      raw(&n, sizeof n);
      if (loading_) {
        need(n, 1);
        v.assign(bytes_.data() + pos_, n);
        pos_ += n;
      } else {
        bytes_.append(v);
      }
    } else if constexpr (is_vector<T>::value) {
      using E = typename T::value_type;
      std::uint64_t n = v.size();
      raw(&n, sizeof n);
      if constexpr (std::is_same_v<E, bool>) {
        static_assert(!std::is_same_v<E, bool>, "std::vector<bool> has no bytes to store");
      } else if constexpr (std::is_trivially_copyable_v<E>) {
        if (loading_) {
          need(n, sizeof(E));
          v.resize(n);
        }
        raw(v.data(), n * sizeof(E));
      } else {
        if (loading_) {
          need(n, 1);  // every element takes at least a byte
          v.resize(n);
        }
        for (auto& e : v) io(e);
      }
    } else if constexpr (has_persist<T>::value) {
      v.persist(*this);
    } else if constexpr (is_pair<T>::value) {
      io(v.first), io(v.second);
    } else if constexpr (std::is_base_of_v<Eigen::QuaternionBase<T>, T>) {
      raw(v.coeffs().data(), 4 * sizeof(typename T::Scalar));
    } else if constexpr (std::is_base_of_v<Eigen::EigenBase<T>, T>) {
      static_assert(T::SizeAtCompileTime > 0, "only fixed-size Eigen objects");
      raw(v.data(), T::SizeAtCompileTime * sizeof(typename T::Scalar));
    } else {
      static_assert(std::is_trivially_copyable_v<T>, "give this type a persist() or store its members");
      raw(&v, sizeof(T));
    }
  }
  void raw(void* p, std::size_t n) {
    if (n == 0) return;
    if (loading_) {
      need(n, 1);
      std::memcpy(p, bytes_.data() + pos_, n);
      pos_ += n;
    } else {
      bytes_.append(static_cast<const char*>(p), n);
    }
  }
  void need(std::uint64_t n, std::size_t size) const {
    DSPDEM_CHECK(n <= remaining() / size,
                 "checkpoint '{}' is truncated or corrupt: {} x {} bytes wanted at byte {} of {}", source_, n, size,
                 pos_, bytes_.size());
  }
  template <class T>
  struct is_vector : std::false_type {};
  template <class E, class A>
  struct is_vector<std::vector<E, A>> : std::true_type {};
  template <class T, class = void>
  struct has_persist : std::false_type {};
  template <class T>
  struct has_persist<T, std::void_t<decltype(std::declval<T&>().persist(std::declval<StateArchive&>()))>>
      : std::true_type {};
  template <class T>
  struct is_pair : std::false_type {};
  template <class A, class B>
  struct is_pair<std::pair<A, B>> : std::true_type {};

  bool loading_ = false;
  std::string bytes_, source_;
  std::size_t pos_ = 0;
};

}  // namespace dspdem
