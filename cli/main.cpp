#include "cli/cli.hpp"

int main(int argc, char** argv) { return fibermold::fibermold_main(argc, argv); }
