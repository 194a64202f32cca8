// A list of types to iterate at compile time: the registry's map back ends and association strategies.
#ifndef ARBOR_VARIANTS_TYPE_LIST_H_
#define ARBOR_VARIANTS_TYPE_LIST_H_

namespace arbor {

template <class... T>
struct TypeList {};

}  // namespace arbor

#endif  // ARBOR_VARIANTS_TYPE_LIST_H_
