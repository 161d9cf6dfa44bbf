// accuracy_variants.cpp - the list of variants (host/studies/accuracy_variants.h); each factory lives in
// its own translation unit, host/accuracy_variant_<name>.cpp.
#include "host/studies/accuracy_variants.h"

namespace openpbr::host {

BsdfVariant make_variant_shipped(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_compensation_none(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_compensation_analytic(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_table_16(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_table_64(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_table_buffer(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_table_half(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_fast_rcp_sqrt(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_fast_sqrt(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_fast_normalize(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_fast_all(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_vndf_hemisphere(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_vndf_bounded(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_thin_film_fast(const std::string& knob, const std::string& setting);
BsdfVariant make_variant_double(const std::string& knob, const std::string& setting);

namespace {

// The variant with its Slang conformance-kernel settings (host/studies/accuracy_variants.h).
BsdfVariant on_slang(BsdfVariant variant, std::vector<std::string> defines, AccuracyTable table = AccuracyTable::shipped)
{
    variant.slang_defines = std::move(defines);
    variant.table = table;
    return variant;
}

}  // namespace

std::vector<BsdfVariant> bsdf_variants()
{
    // The Slang defines are each C++ variant file's macros (the headers define the names the
    // values refer to, which the preprocessor expands where the knob is tested).
    BsdfVariant table_buffer = make_variant_table_buffer("table storage", "float32 buffer");
    table_buffer.on_vulkan = false;
    table_buffer.bit_identical_to_shipped = true;
    // The precision knob: the shipped build once more under its own name, and the double build.
    BsdfVariant single_precision = make_variant_shipped("precision", "C++ float (shipped)");
    single_precision.on_vulkan = false;
    BsdfVariant double_precision = make_variant_double("precision", "C++ double");
    double_precision.on_vulkan = false;
    double_precision.double_reference = true;
    return {
        on_slang(make_variant_shipped("shipped", "tables 32 (array), spherical caps, full thin film"), {}),
        on_slang(make_variant_compensation_none("compensation", "none"), {"OPENPBR_COMPENSATION_MODE=OPENPBR_COMPENSATION_NONE"}),
        on_slang(make_variant_compensation_analytic("compensation", "analytic fit (15-term polynomial)"),
                 {"OPENPBR_COMPENSATION_MODE=OPENPBR_COMPENSATION_ANALYTIC"}),
        on_slang(make_variant_table_16("compensation", "table 16x16"), {"OPENPBR_LUT_2D_SIZE=16"}, AccuracyTable::size_16),
        on_slang(make_variant_table_64("compensation", "table 64x64"), {"OPENPBR_LUT_2D_SIZE=64"}, AccuracyTable::size_64),
        table_buffer,
        on_slang(make_variant_table_half("table storage", "16-bit values (buffer)"), {"OPENPBR_LUT_16BIT=1"},
                 AccuracyTable::half),
        on_slang(make_variant_fast_rcp_sqrt("fast math", "OPENPBR_FAST_RCP_SQRT"), {"OPENPBR_FAST_RCP_SQRT=1"}),
        on_slang(make_variant_fast_sqrt("fast math", "OPENPBR_FAST_SQRT + RCP_SQRT"),
                 {"OPENPBR_FAST_SQRT=1", "OPENPBR_FAST_RCP_SQRT=1"}),
        on_slang(make_variant_fast_normalize("fast math", "OPENPBR_FAST_NORMALIZE + RCP_SQRT"),
                 {"OPENPBR_FAST_NORMALIZE=1", "OPENPBR_FAST_RCP_SQRT=1"}),
        on_slang(make_variant_fast_all("fast math", "all hooks"),
                 {"OPENPBR_FAST_RCP_SQRT=1", "OPENPBR_FAST_SQRT=1", "OPENPBR_FAST_NORMALIZE=1"}),
        on_slang(make_variant_vndf_hemisphere("vndf sampling", "Heitz 2018 hemisphere"), {"OPENPBR_VNDF_METHOD=OPENPBR_VNDF_METHOD_HEMISPHERE"}),
        on_slang(make_variant_vndf_bounded("vndf sampling", "bounded (Eto & Tokuyoshi 2023)"), {"OPENPBR_VNDF_METHOD=OPENPBR_VNDF_METHOD_BOUNDED"}),
        on_slang(make_variant_thin_film_fast("thin film", "fast thin film approximation"), {"OPENPBR_THIN_FILM_MODEL=OPENPBR_THIN_FILM_MODEL_FAST"}),
        single_precision,
        double_precision,
    };
}

}  // namespace openpbr::host
