#include "shadetlm/tlm/block.hpp"

#include <algorithm>
#include <stdexcept>

#include "shadetlm/core/input_error.hpp"

namespace shadetlm::modules {

std::vector<std::string> PipelineDecl::block_names() const {
  std::vector<std::string> names;
  for (const auto& pass : passes)
    for (const auto& b : pass.blocks) names.push_back(b.name);
  return names;
}

std::vector<core::SettingSpec> PipelineDecl::all_settings() const {
  std::vector<core::SettingSpec> all = settings;
  for (const auto& pass : passes)
    for (const auto& b : pass.blocks) {
      for (core::SettingSpec& s : core::specs_of(b.basics, b.name + ".")) all.push_back(std::move(s));
      for (core::SettingSpec s : b.settings) {
        s.key = b.name + "." + s.key;
        all.push_back(std::move(s));
      }
    }
  return all;
}

std::optional<CacheConfig> cache_of(const BlockContext& ctx) {
  if (ctx.pipeline.memory == PipelineSettings::Memory::Ideal) return std::nullopt;
  const CacheFault fault = check(ctx.basics.cache);
  if (!fault.setting.empty())
    throw core::InputError(ctx.scene.file, "pipeline." + ctx.name + ".cache." + fault.setting, fault.why);
  return ctx.basics.cache;
}

void PipelineDecl::insert_after(const std::string& after, BlockDecl block) {
  const auto names = block_names();
  if (std::find(names.begin(), names.end(), block.name) != names.end())
    throw std::invalid_argument("the pipeline has a block named " + block.name + " already");
  for (auto& pass : passes)
    for (auto it = pass.blocks.begin(); it != pass.blocks.end(); ++it)
      if (it->name == after) {
        pass.blocks.insert(it + 1, std::move(block));
        return;
      }
  throw std::invalid_argument("the pipeline has no block named " + after);
}

}  // namespace shadetlm::modules
