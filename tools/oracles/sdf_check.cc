// Loads an SDF file with SDFormat's own parser (libsdformat) and prints what it found:
//   error: <message>            one line per error (exit status 1 if any)
//   model <name> links=<n> joints=<n>
//   joint <model>/<name> <type> lower=<rad> upper=<rad>
// Used by semsim's export tests as the reference reader of SDF.
#include <sdf/sdf.hh>
#include <iostream>

static const char *type_name(sdf::JointType t) {
  switch (t) {
    case sdf::JointType::REVOLUTE: return "revolute";
    case sdf::JointType::CONTINUOUS: return "continuous";
    case sdf::JointType::FIXED: return "fixed";
    case sdf::JointType::PRISMATIC: return "prismatic";
    case sdf::JointType::BALL: return "ball";
    default: return "other";
  }
}

static void print_model(const sdf::Model *model, const std::string &prefix) {
  const std::string name = prefix + model->Name();
  std::cout << "model " << name << " links=" << model->LinkCount()
            << " joints=" << model->JointCount() << "\n";
  for (uint64_t j = 0; j < model->JointCount(); ++j) {
    const sdf::Joint *joint = model->JointByIndex(j);
    double lower = 0, upper = 0;
    if (const sdf::JointAxis *axis = joint->Axis(0)) {
      lower = axis->Lower();
      upper = axis->Upper();
    }
    std::cout << "joint " << name << "/" << joint->Name() << " " << type_name(joint->Type())
              << " lower=" << lower << " upper=" << upper << "\n";
  }
  for (uint64_t m = 0; m < model->ModelCount(); ++m)
    print_model(model->ModelByIndex(m), name + "::");
}

int main(int argc, char **argv) {
  if (argc != 2) {
    std::cerr << "usage: sdf_check FILE.sdf\n";
    return 2;
  }
  std::cout.precision(17);  // every digit of a double: the tests compare within 1e-6
  sdf::Root root;
  const sdf::Errors errors = root.Load(argv[1]);
  for (const auto &e : errors) std::cout << "error: " << e.Message() << "\n";
  for (uint64_t w = 0; w < root.WorldCount(); ++w) {
    const sdf::World *world = root.WorldByIndex(w);
    std::cout << "world " << world->Name() << " models=" << world->ModelCount() << "\n";
    for (uint64_t m = 0; m < world->ModelCount(); ++m) print_model(world->ModelByIndex(m), "");
  }
  if (const sdf::Model *model = root.Model()) print_model(model, "");
  return errors.empty() ? 0 : 1;
}
