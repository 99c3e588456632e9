#pragma once
namespace stickslip {
inline constexpr const char* kVersion = "0.1.0";
}
