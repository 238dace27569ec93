# Sourced by the example tests, after `build` and `source` are set: makes a scratch
# directory $work (removed on exit), installs moorsim from $build into $work/prefix and
# builds examples/NAME against it with find_package(moorsim) into $work/NAME.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"

build_example() {
  cmake -S "$source/examples/$1" -B "$work/$1" -DCMAKE_PREFIX_PATH="$work/prefix" \
    >"$work/configure-$1.log"
  cmake --build "$work/$1" >"$work/build-$1.log"
}
