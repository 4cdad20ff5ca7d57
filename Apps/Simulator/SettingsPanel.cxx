#include "SettingsPanel.h"

#include "ThinTissueError.h"

#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>

#include <nlohmann/json.hpp>

namespace thintissue
{

namespace
{

struct Setting
{
  const char* key;
  const char* label;
};

constexpr Setting Settings[] = {
  { "tissue.material.youngModulus", "Young's modulus (MPa)" },
  { "tissue.material.poissonRatio", "Poisson's ratio" },
  { "tissue.material.density", "density (t/mm\u00b3)" },
  { "tissue.wrinkle.frequency", "wrinkle frequency \u03b8\u1d48" },
  { "tissue.wrinkle.scale", "wrinkle scale s" },
  { "tissue.wrinkle.magnitudeBound", "wrinkle bound m\u1d58\u1d56 (mm)" },
  { "tissue.wrinkle.windowSize", "wrinkle window (points)" },
  { "cutting.cutSurfaceRows", "cut-surface rows" },
  { "cutting.fragmentAreaFraction", "fragments removed below (area fraction)" },
};

/// A setting's value in the scenario.
double valueOf(const ScenarioDescription& s, const std::string& key)
{
  const std::map<std::string, double> values = {
    { "tissue.material.youngModulus", s.material.youngModulus },
    { "tissue.material.poissonRatio", s.material.poissonRatio },
    { "tissue.material.density", s.material.density },
    { "tissue.wrinkle.frequency", s.wrinkle.frequency },
    { "tissue.wrinkle.scale", s.wrinkle.scale },
    { "tissue.wrinkle.magnitudeBound", s.wrinkle.magnitudeBound },
    { "tissue.wrinkle.windowSize", s.wrinkle.windowSize },
    { "cutting.cutSurfaceRows", s.cutSurfaceRows },
    { "cutting.fragmentAreaFraction", s.fragmentAreaFraction },
  };
  return values.at(key);
}

} // namespace

SettingsPanel::SettingsPanel(Starter start, QWidget* parent)
  : QWidget(parent)
  , Start(std::move(start))
{
  auto* form = new QFormLayout(this);
  for (const Setting& setting : Settings)
  {
    auto* edit = new QLineEdit(this);
    edit->setToolTip(setting.key);
    form->addRow(QString::fromUtf8(setting.label), edit);
    Fields[setting.key] = edit;
  }
  auto* button =
    new QPushButton("Apply (the cut surface's settings restart a cutting scenario)", this);
  form->addRow(button);
  Message = new QLabel(this);
  Message->setWordWrap(true);
  Message->setStyleSheet("color: #c02020");
  form->addRow(Message);
  connect(button, &QPushButton::clicked, this, [this] { apply(); });
}

void SettingsPanel::show(const ScenarioDescription& scenario)
{
  Running = scenario;
  for (const auto& [key, edit] : Fields)
  {
    edit->setText(QString::number(valueOf(scenario, key), 'g', 10));
  }
}

QLineEdit* SettingsPanel::field(const std::string& key) const
{
  return Fields.at(key);
}

QString SettingsPanel::error() const
{
  return Message->text();
}

std::string SettingsPanel::settingsJson() const
{
  nlohmann::json root = nlohmann::json::object();
  for (const auto& [key, edit] : Fields)
  {
    bool number = false;
    const double value = edit->text().trimmed().toDouble(&number);
    if (!number)
    {
      throw InvalidInputError(
        "settings: key '" + key + "': '" + edit->text().toStdString() + "' is not a number");
    }
    root[nlohmann::json::json_pointer(
      "/" + QString::fromStdString(key).replace('.', '/').toStdString())] = value;
  }
  return root.dump();
}

bool SettingsPanel::apply()
{
  try
  {
    const ScenarioDescription changed = applyScenarioSettings(Running, settingsJson(), "settings");
    Message->clear();
    if (!Start(changed))
    {
      Message->setText("the scenario did not start with these settings (see the message)");
      return false;
    }
    return true;
  }
  catch (const Error& e)
  {
    Message->setText(QString::fromStdString(e.what()));
    return false;
  }
}

} // namespace thintissue
