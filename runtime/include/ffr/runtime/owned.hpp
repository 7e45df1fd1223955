#pragma once
// A heap-held object with value semantics: copying the holder copies the object. Data holds the
// relative formulation's workspace this way, so a copied Data (a branch of a simulation) gets its
// own workspace instead of sharing one with the original, as with every other member of Data.
//
// T may be incomplete where the holder is declared: the copy and the deletion are bound where the
// object is made (`make`), where T is complete.
#include <utility>

namespace ffr::runtime {

template <class T>
class Owned {
 public:
  Owned() = default;

  template <class... Args>
  static Owned make(Args&&... args) {
    Owned o;
    o.p_ = new T(std::forward<Args>(args)...);
    o.copy_ = [](const T* p) { return new T(*p); };
    o.delete_ = [](T* p) { delete p; };
    return o;
  }

  Owned(const Owned& o) : p_(o.p_ ? o.copy_(o.p_) : nullptr), copy_(o.copy_), delete_(o.delete_) {}
  Owned(Owned&& o) noexcept : p_(std::exchange(o.p_, nullptr)), copy_(o.copy_), delete_(o.delete_) {}
  Owned& operator=(Owned o) noexcept {
    std::swap(p_, o.p_);
    std::swap(copy_, o.copy_);
    std::swap(delete_, o.delete_);
    return *this;
  }
  ~Owned() {
    if (p_) delete_(p_);
  }

  explicit operator bool() const { return p_ != nullptr; }
  T& operator*() { return *p_; }
  const T& operator*() const { return *p_; }
  T* operator->() { return p_; }
  const T* operator->() const { return p_; }

 private:
  T* p_ = nullptr;
  T* (*copy_)(const T*) = nullptr;
  void (*delete_)(T*) = nullptr;
};

}  // namespace ffr::runtime
