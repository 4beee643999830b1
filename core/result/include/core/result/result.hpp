#pragma once
// A value or a typed error: C++20 has no std::expected and the core may not throw. Every
// driver of the core returns its errors through this one template with its own error enum.
namespace ap {

template <class T, class E>
class Result {
 public:
  constexpr Result(T value) : value_(value), ok_(true) {}     // NOLINT: implicit on purpose
  constexpr Result(E error) : value_{}, error_(error) {}      // NOLINT: implicit on purpose
  constexpr bool ok() const { return ok_; }
  constexpr explicit operator bool() const { return ok_; }
  constexpr const T& value() const { return value_; }
  constexpr const T& operator*() const { return value_; }
  constexpr E error() const { return error_; }

 private:
  T value_;
  E error_{};
  bool ok_ = false;
};

}  // namespace ap
