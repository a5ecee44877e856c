#include "app/check/setup_checks.h"

#include <exception>
#include <future>
#include <ostream>

#include "app/check/region_checks.h"
#include "model/plausibility.h"
#include "model/source_checks.h"

namespace peensim {

std::size_t report_setup_issues(const std::vector<AssemblyIssue>& issues, bool strict, std::ostream& err) {
    const AssemblyIssue* fatal = nullptr;
    for (const AssemblyIssue& i : issues)
        if (i.error && fatal == nullptr) fatal = &i;
    if (fatal == nullptr && strict)
        for (const AssemblyIssue& i : issues)
            if (fatal == nullptr) fatal = &i;
    std::size_t warnings = 0;
    for (const AssemblyIssue& i : issues) {
        warnings += !i.error;
        if (&i != fatal) err << (i.error ? "error: " : "warning: ") << InputError::format(i.where, i.field, i.message) << "\n";
    }
    if (fatal != nullptr) throw InputError(fatal->where, fatal->field, fatal->message + (fatal->error ? "" : " (an error with --strict)"));
    return warnings;
}

SetupCheck check_setup(const Model& model, bool strict, std::ostream& err, std::vector<AssemblyIssue>* found) {
    SetupCheck s{Random(model.seed), nullptr, {}, 0, {}};
    s.warnings = report_setup_issues(plausibility_issues(model), strict, err);
    // The parts' region tallies and the shot's cavity read the model only: made side by side (on
    // the 500k-triangle gear 0.2 s on two cores and 0.25 s on one, one after the other), and
    // reported in the order of the checks (a cavity that fails says so after the regions' issues).
    auto regions = std::async(std::launch::async, [&model] { return component_regions(model); });
    std::exception_ptr cavity_failure;
    try {
        if (model.sonotrode >= 0) s.cavity = std::make_unique<ShotCavity>(model, s.rng);
    } catch (...) {
        cavity_failure = std::current_exception();
    }
    s.regions = regions.get();
    s.warnings += report_setup_issues(region_issues(model, s.regions), strict, err);
    s.warnings += report_setup_issues(source_issues(model), strict, err);
    if (cavity_failure) std::rethrow_exception(cavity_failure);
    s.assembly = check_assembly(model, s.cavity.get());
    if (found) *found = s.assembly.issues;
    s.warnings += report_setup_issues(s.assembly.issues, strict, err);
    return s;
}

}  // namespace peensim
