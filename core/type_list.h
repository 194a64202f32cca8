// A list of types to iterate at compile time (the registry's map back ends, the association strategies' list). In
// core/ so that variants/ can name lists in its folders and gather them in its registry without an include loop.
#ifndef ARBOR_CORE_TYPE_LIST_H_
#define ARBOR_CORE_TYPE_LIST_H_

namespace arbor {

template <class... T>
struct TypeList {};

}  // namespace arbor

#endif  // ARBOR_CORE_TYPE_LIST_H_
