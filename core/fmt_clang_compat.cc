// clang builds (the sanitizer stage) link Debian's libfmt, which gcc built. For one function template,
// fmt::detail::vformat_to<char>, the two compilers mangle the name differently (clang keeps the alias
// std::conditional<...>::type in its format-context argument), so a unit that formats through fmt/core.h
// alone finds no definition in the library. Instantiating it here, once, gives clang builds the symbol under
// the name clang expects; gcc builds need nothing. (FMT_HEADER_ONLY would also do, at about 16 s more
// compile time for every unit that uses fmt.)
#if defined(__clang__) && !defined(FMT_HEADER_ONLY)
#include <fmt/format.h>

template void fmt::detail::vformat_to<char>(fmt::detail::buffer<char>&, fmt::basic_string_view<char>,
                                            fmt::basic_format_args<FMT_BUFFER_CONTEXT(char)>,
                                            fmt::detail::locale_ref);
#endif
