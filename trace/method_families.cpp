// The --method name table, generated from MethodFamilyTable.
#include "trace/method_families.h"

namespace rtlab {

const std::vector<MethodFamily>& method_families() {
    static const std::vector<MethodFamily> families = [] {
        std::vector<MethodFamily> out;
        for_each_type<MethodFamilyTable>([&]<class Family>() {
            out.push_back({Family::name, family_method_names<Family>()});
        });
        return out;
    }();
    return families;
}

}  // namespace rtlab
