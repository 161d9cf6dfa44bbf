// The model-against-reference study (host/studies/layering_accuracy.h) in a quick mode: rows for
// every material and view, the JSON row schema other studies read, and the two sides agreeing
// where the model is exact by construction.
#include <gtest/gtest.h>

#include <cmath>

#include "host/studies/layering_accuracy.h"
#include "slang/openpbr.h"

namespace {

using openpbr::host::LayeringMaterial;
using openpbr::host::LayeringOptions;

LayeringOptions quick_options()
{
    LayeringOptions options;
    options.view_cosines = {1.0, 0.5};
    options.reference_paths = 1u << 12;
    options.model_samples = 1u << 14;
    options.timing_queries = 64;
    options.progress = false;
    return options;
}

// A rough white metal is one layer, which the model's compensated lobe reproduces to within the
// compensation's own error: measured |model - reference| 0.003-0.004 at cos 1 and 0.5 (reference
// standard error 0: every path leaves with weight 1); asserted below 0.02. A coloured coat over
// a diffuse is off by more (0.09-0.10, docs/layering-accuracy.md): its rows are only checked to
// be complete, its coat_darkening 0.5 replaced by 1 and said so.
TEST(LayeringStudy, RowsForEveryMaterialAndView)
{
    LayeringMaterial white_metal{"white metal", "test", openpbr::openpbr_make_default_resolved_inputs()};
    white_metal.inputs.base_metalness = 1.0f;
    white_metal.inputs.base_color = glm::vec3(1.0f);
    white_metal.inputs.specular_roughness = 0.5f;
    LayeringMaterial coated{"coated", "test", openpbr::openpbr_make_default_resolved_inputs()};
    coated.inputs.coat_weight = 1.0f;
    coated.inputs.coat_color = glm::vec3(0.8f, 0.6f, 0.4f);
    coated.inputs.coat_darkening = 0.5f;
    const auto rows = openpbr::host::run_layering_study({white_metal, coated}, quick_options());
    ASSERT_EQ(rows.size(), 4u);
    for (const auto& row : rows)
    {
        EXPECT_TRUE(std::isfinite(row.shape_error)) << row.material;
        EXPECT_GE(row.shape_error, 0.0);
        EXPECT_LE(row.shape_error, 1.0);
        EXPECT_GT(row.model_ns, 0.0);
        EXPECT_GT(row.reference_ns, 0.0);
        for (std::size_t c = 0; c < 3; ++c)
        {
            EXPECT_GE(row.reference_albedo[c], 0.0);
            EXPECT_LE(row.reference_albedo[c], 1.0 + 4.0 * row.reference_standard_error[c]);
            EXPECT_TRUE(std::isfinite(row.model_albedo[c]));
        }
        if (row.material == "white metal")
        {
            EXPECT_LT(row.albedo_error, 0.02) << row.view_cosine;
        }
    }
    EXPECT_NE(rows[2].note.find("coat_darkening"), std::string::npos);
}

// The JSON keeps the row schema the accuracy study's figures read.
TEST(LayeringStudy, JsonRowSchema)
{
    LayeringMaterial material{"default", "test", openpbr::openpbr_make_default_resolved_inputs()};
    LayeringOptions options = quick_options();
    options.view_cosines = {0.7};
    const auto rows = openpbr::host::run_layering_study({material}, options);
    const nlohmann::json document = openpbr::host::layering_to_json(rows, options, 1.0);
    ASSERT_EQ(document.at("rows").size(), 1u);
    const nlohmann::json& row = document.at("rows").at(0);
    EXPECT_EQ(row.at("material"), "default");
    EXPECT_EQ(row.at("view_cosine"), 0.7);
    for (const char* key : {"model_albedo", "reference_albedo", "reference_standard_error"})
    {
        ASSERT_EQ(row.at(key).size(), 3u) << key;
    }
    for (const char* key : {"shape_error", "model_ns", "reference_ns"})
    {
        EXPECT_TRUE(row.at(key).is_number()) << key;
    }
    EXPECT_TRUE(document.at("summary").is_object());
}

}  // namespace
