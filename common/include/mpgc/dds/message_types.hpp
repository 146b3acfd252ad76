// The generated message type of an IDL name, for code that handles every topic alike (replay, the
// recorder's tests): with_message_type("mpgc::msg::NavState", [](auto* tag) { using T =
// std::remove_pointer_t<decltype(tag)>; ... }) calls the function with a null T* and returns
// true, or returns false when no type of idl/ has that name.
#pragma once

#include <string>

#include "mpgc/msg/all.hpp"

namespace mpgc::msg {

namespace detail {
template <class F, class... T>
bool with_type_in(dds::TypeList<T...>, const std::string& name, F& f) {
  return ((name == T::type_name ? (f(static_cast<T*>(nullptr)), true) : false) || ...);
}
}  // namespace detail

template <class F>
bool with_message_type(const std::string& name, F&& f) {
  return detail::with_type_in(core_types{}, name, f) || detail::with_type_in(nav_types{}, name, f) ||
         detail::with_type_in(sensors_types{}, name, f) || detail::with_type_in(tracks_types{}, name, f) ||
         detail::with_type_in(obstacles_types{}, name, f) || detail::with_type_in(plan_types{}, name, f) ||
         detail::with_type_in(control_types{}, name, f);
}

}  // namespace mpgc::msg
