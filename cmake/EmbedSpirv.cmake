# cmake -DSPV=in.spv -DCPP=out.cpp -DSYMBOL=name -DNAMESPACE=ns -P EmbedSpirv.cmake
# Writes the SPIR-V words (little-endian file) as a uint32_t array.
file(READ "${SPV}" hex HEX)
string(LENGTH "${hex}" length)
math(EXPR remainder "${length} % 8")
if(NOT remainder EQUAL 0 OR length EQUAL 0)
  message(FATAL_ERROR "${SPV} is not a whole number of 32-bit words")
endif()
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
string(REGEX REPLACE "((0x........u,){8})" "\\1\n" words "${words}")
file(WRITE "${CPP}" "// Generated from ${SPV}
#include <cstdint>
#include <span>
namespace ${NAMESPACE} {
namespace {
const std::uint32_t k_words[] = {
${words}
};
}  // namespace
std::span<const std::uint32_t> ${SYMBOL}() { return k_words; }
}  // namespace ${NAMESPACE}
")
