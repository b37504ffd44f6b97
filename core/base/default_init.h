#pragma once
// A std::vector allocator whose value-less construction default-initialises: a vector of
// trivial elements is sized without being zeroed. A large array filled by a parallel loop then
// takes its first-touch page faults on every thread, where the loop writes, instead of in one
// serial memset when it is sized (a 2 M-triangle TriangleBvh: about a second of one thread;
// also the triangle schemes' update-row discs, core/schemes/tri/tri_transform.cpp).
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace sublift {

template <class T>
struct DefaultInit : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = DefaultInit<U>;
  };
  DefaultInit() = default;
  template <class U>
  DefaultInit(const DefaultInit<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A vector whose resize leaves trivial elements uninitialised (fill them before reading).
template <class T>
using UninitVector = std::vector<T, DefaultInit<T>>;

}  // namespace sublift
