// accuracy_variants.cpp - the list of variants (host/accuracy_variants.h); each factory lives in
// its own translation unit, host/accuracy_variant_<name>.cpp.
#include "host/accuracy_variants.h"

namespace openpbr::host {

BsdfVariant make_variant_shipped(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_compensation_none(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_compensation_analytic(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_table_16(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_table_64(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_table_half(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_fast_rcp_sqrt(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_fast_sqrt(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_fast_normalize(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_fast_all(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_vndf_hemisphere(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_vndf_bounded(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_thin_film_fast(const std::string& knob, const std::string& setting);

std::vector<BsdfVariant> bsdf_variants()
{
    return {
        make_variant_shipped("shipped", "tables 32 (array), spherical caps, full thin film"),
        make_variant_compensation_none("compensation", "none"),
        make_variant_compensation_analytic("compensation", "analytic fit (15-term polynomial)"),
        make_variant_table_16("compensation", "table 16x16"),
        make_variant_table_64("compensation", "table 64x64"),
        make_variant_table_half("table storage", "16-bit values (buffer)"),
        make_variant_fast_rcp_sqrt("fast math", "OPENPBR_FAST_RCP_SQRT"),
        make_variant_fast_sqrt("fast math", "OPENPBR_FAST_SQRT + RCP_SQRT"),
        make_variant_fast_normalize("fast math", "OPENPBR_FAST_NORMALIZE + RCP_SQRT"),
        make_variant_fast_all("fast math", "all hooks"),
        make_variant_vndf_hemisphere("vndf sampling", "Heitz 2018 hemisphere"),
        make_variant_vndf_bounded("vndf sampling", "bounded (Eto & Tokuyoshi 2023)"),
        make_variant_thin_film_fast("thin film", "fast thin film approximation"),
    };
}

}  // namespace openpbr::host
