// tyndall-render: renders a scene file through the stub host with Tyndall in its post-process
// stack. Command line: see `tyndall-render --help` and DESIGN.md.
#include "render_job.h"

int main(int argc, char** argv) { return tyndall::samples::runTyndallRender(argc, argv); }
