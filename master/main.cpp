// prism: the one executable. Subcommands are described by `prism --help`.
#include "master/Cli.h"

int main(int argc, char** argv) {
  return prism::runCli(argc, argv);
}
