// Whether this test binary runs under AddressSanitizer (GCC defines __SANITIZE_ADDRESS__,
// Clang answers __has_feature). Tests that replay long drives or large data sets run a
// smaller share there, where memory checking makes them tens of times slower.
#pragma once

namespace flat2d::testing {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace flat2d::testing
