// Seeded values for every field of an IDL message (its generated visit_fields), for tests that
// must see each field survive a trip: numbers across their range, strings with spaces, quotes,
// UTF-8 and a long one, sequences of 0..4 elements (nested sequences included).
//
//   std::mt19937_64 rng(seed);
//   mpgc::msg::Path p;
//   mpgc::testing::Filler{rng}.fill(p);
#pragma once

#include <array>
#include <cstddef>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace mpgc::testing {

// A generated message type (it has the C type Cyclone serialises it through).
template <class T, class = void>
struct is_message : std::false_type {};
template <class T>
struct is_message<T, std::void_t<typename T::CType>> : std::true_type {};

struct Filler {
  std::mt19937_64& rng;
  template <class T>
  void operator()(const char*, T& v) { fill(v); }

  template <class T>
  void fill(T& v) {
    if constexpr (std::is_same_v<T, bool>) {
      v = (rng() & 1u) != 0;
    } else if constexpr (std::is_floating_point_v<T>) {
      v = static_cast<T>(std::uniform_real_distribution<double>(-1e7, 1e7)(rng));
    } else if constexpr (std::is_integral_v<T>) {
      v = static_cast<T>(rng());
    } else if constexpr (std::is_enum_v<T>) {
      v = static_cast<T>(rng() % 2);  // every enum has at least two enumerators
    } else if constexpr (std::is_same_v<T, std::string>) {
      static const char* samples[] = {"", "ship_simulator", "with spaces and \"quotes\"", "Ærøskøbing ⚓ 北",
                                      "line\nbreak\ttab"};
      const auto k = rng() % 6;
      v = k < 5 ? samples[k] : std::string(3000, static_cast<char>('a' + rng() % 26));
    } else if constexpr (is_message<T>::value) {
      visit_fields(v, *this);
    } else {
      fill_container(v);
    }
  }
  template <class E>
  void fill_container(std::vector<E>& v) {
    v.resize(rng() % 5);
    for (auto& e : v) fill(e);
  }
  template <class E, std::size_t N>
  void fill_container(std::array<E, N>& v) {
    for (auto& e : v) fill(e);
  }
};

}  // namespace mpgc::testing
