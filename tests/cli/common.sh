# Sourced by the command-line test scripts (arguments: WORKBENCH_BINARY SOURCE_DIR): the binary and
# the source folder, a scratch folder removed on exit, and check() counting passed and failed checks.
set -u
bin=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0
failures=0
check() {  # check NAME CONDITION_EXIT_STATUS MESSAGE
  if [ "$2" -eq 0 ]; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL $1: $3"; fi
}
