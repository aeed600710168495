#pragma once
// A span kernel's optional parts (modules/README.md): besides process, bypass, work, ops,
// trace_names, trace and set_capture, a kernel may report ranges(), numbers(),
// details() (JSON), memory() and precompute_seconds(), hand something on in
// end_pass(PassEnd&) and write test vectors (vector_layout(), vector_in(), vector_out()).
// It names the ones it has, and the build checks the names against its methods both ways:
//
//   static constexpr unsigned optional = Optional::numbers | Optional::details;
//
// so a misspelled details() fails to build ("names details but has no details() const")
// instead of never being called.
#include <type_traits>
#include <utility>

#include "shadetlm/tlm/packet.hpp"

namespace shadetlm::modules {

struct Optional {
  enum : unsigned {
    none = 0,
    ranges = 1u << 0,
    numbers = 1u << 1,
    details = 1u << 2,
    memory = 1u << 3,
    precompute = 1u << 4,
    end_pass = 1u << 5,
    vectors = 1u << 6,
  };
};

// The parts as found by their signatures.
template <class K, class = void> struct has_ranges : std::false_type {};
template <class K> struct has_ranges<K, std::void_t<decltype(std::declval<const K&>().ranges())>> : std::true_type {};
template <class K, class = void> struct has_numbers : std::false_type {};
template <class K> struct has_numbers<K, std::void_t<decltype(std::declval<const K&>().numbers())>> : std::true_type {};
template <class K, class = void> struct has_details : std::false_type {};
template <class K> struct has_details<K, std::void_t<decltype(std::declval<const K&>().details())>> : std::true_type {};
template <class K, class = void> struct has_memory : std::false_type {};
template <class K> struct has_memory<K, std::void_t<decltype(std::declval<const K&>().memory())>> : std::true_type {};
template <class K, class = void> struct has_precompute : std::false_type {};
template <class K>
struct has_precompute<K, std::void_t<decltype(std::declval<const K&>().precompute_seconds())>> : std::true_type {};
template <class K, class = void> struct has_vectors : std::false_type {};
template <class K>
struct has_vectors<K, std::void_t<decltype(std::declval<const K&>().vector_layout())>> : std::true_type {};
// (has_end_pass is in packet.hpp, beside PassEnd.)
template <class K, class = void> struct names_optional : std::false_type {};
template <class K> struct names_optional<K, std::void_t<decltype(K::optional)>> : std::true_type {};

// True, or a build error naming the part where K's `optional` and its methods disagree.
template <class K>
constexpr bool optional_parts_checked() {
  static_assert(names_optional<K>::value,
                "a span kernel names its optional parts: static constexpr unsigned optional = Optional::… "
                "(Optional::none if it has none; tlm/kernel_parts.hpp)");
  if constexpr (names_optional<K>::value) {
    constexpr unsigned o = K::optional;
    static_assert(bool(o & Optional::ranges) == has_ranges<K>::value,
                  "the kernel's optional names ranges exactly when it has ranges() const");
    static_assert(bool(o & Optional::numbers) == has_numbers<K>::value,
                  "the kernel's optional names numbers exactly when it has numbers() const");
    static_assert(bool(o & Optional::details) == has_details<K>::value,
                  "the kernel's optional names details exactly when it has details() const");
    static_assert(bool(o & Optional::memory) == has_memory<K>::value,
                  "the kernel's optional names memory exactly when it has memory() const");
    static_assert(bool(o & Optional::precompute) == has_precompute<K>::value,
                  "the kernel's optional names precompute exactly when it has precompute_seconds() const");
    static_assert(bool(o & Optional::end_pass) == has_end_pass<K>::value,
                  "the kernel's optional names end_pass exactly when it has end_pass(PassEnd&)");
    static_assert(bool(o & Optional::vectors) == has_vectors<K>::value,
                  "the kernel's optional names vectors exactly when it has vector_layout() const");
  }
  return true;
}

}  // namespace shadetlm::modules
