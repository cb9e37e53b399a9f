// The `weft` command (run_weft, app/cli/command.h). The command table and its options are
// compiled into weft_cli, so that this file, built after it, costs nothing.
#include "app/cli/command.h"

int main(int argc, char** argv) { return weft::app::run_weft(argc, argv); }
