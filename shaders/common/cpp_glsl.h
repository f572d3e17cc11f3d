// Lets one source be compiled both as GLSL and as C++ (with GLM), as NVIDIA NRD and DiligentFX
// do for their constant blocks: the shaders and the unit tests then run the same arithmetic.
// Rules for shared code: float literals carry an `f`, only GLM-compatible built-ins, no `inout`
// (use TYN_INOUT), no swizzle assignment; functions start with TYN_FUNC (inline in C++).
#ifndef TYNDALL_CPP_GLSL_H
#define TYNDALL_CPP_GLSL_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
#define TYN_BEGIN namespace tyndall::gpu { using namespace glm; using uint = std::uint32_t;
#define TYN_END }
#define TYN_INOUT(type) type&
#define TYN_CONST inline constexpr
#define TYN_FUNC inline
#else
#define TYN_BEGIN
#define TYN_END
#define TYN_INOUT(type) inout type
#define TYN_CONST const
#define TYN_FUNC
#endif

#endif
