#!/bin/sh
# tests/cmake_check.sh - hairfur.h as other builds find it. The
# repository's CMakeLists.txt is configured and installed with
# cmake --install --prefix, then tests/cmake_consumer (a program that
# includes <hairfur.h>, defines the implementation and links
# hairfur::hairfur) is configured, built with -Wall -Wextra -Wpedantic
# -Werror as C99, and run three ways: find_package after the install (asking
# for the header's major.minor; asking for 99.0 must fail), add_subdirectory
# of this checkout, and FetchContent of an archive of it (a file:// URL and
# its SHA-256, no network). CMake's own warnings are errors. Then
# pkg-config: the same main.c compiled with cc and the flags of the
# installed hairfur.pc, once from cmake --install and once from
# make install PREFIX=... . Each program must print the header's version.
#
# Everything goes under build/cmake-check/ (remade on each run). Skips (exit
# 0, with the reason) where cmake is missing; the pkg-config part likewise
# without pkg-config. Run from the repository root.
set -u
B=build/cmake-check
if ! command -v cmake >/dev/null 2>&1; then
    echo "cmake-check: SKIP: cmake is missing (Debian package cmake: make deps)"
    exit 0
fi
start=$(date +%s)
root=$(pwd)
out=$root/$B
rm -rf "$out" && mkdir -p "$out" || exit 1
version=$(sed -n 's/^#define HAIRFUR_VERSION_STRING "\([0-9.]*\)"$/\1/p' hairfur.h)
if [ -z "$version" ]; then
    echo "cmake-check: FAIL: no HAIRFUR_VERSION_STRING in hairfur.h"; exit 1
fi
major_minor=${version%.*}
want="cmake_consumer: hairfur $version ("
STRICT="-Wall -Wextra -Wpedantic -Werror"
fail=0
bad() { echo "cmake-check: FAIL: $*"; fail=1; }

# step NAME COMMAND...: runs it, output into $B/NAME.log; on failure says
# so with the log's tail
step() {
    step_name=$1; shift
    "$@" >"$out/$step_name.log" 2>&1 && return 0
    bad "$step_name: $* exited $? (log $B/$step_name.log):"
    tail -n 15 "$out/$step_name.log"
    return 1
}

# run_consumer NAME PROGRAM: runs it; it must exit 0 and print the version
run_consumer() {
    "$2" >"$out/$1.out" 2>&1; rc=$?
    case "$(cat "$out/$1.out")" in
        "$want"*) [ $rc -eq 0 ] && { echo "cmake-check: $1: $(cat "$out/$1.out")"; return 0; } ;;
    esac
    bad "$1: $2 exited $rc, printed: $(head -c 300 "$out/$1.out")"
    return 1
}

# no_warning NAME: $B/NAME.log has no CMake warning
no_warning() {
    ! grep -q "CMake Warning" "$out/$1.log" ||
        bad "$1: CMake warned: $(grep -A3 "CMake Warning" "$out/$1.log" | tr -s ' \n' ' ')"
}

# consumer NAME CMAKE_ARGS...: configure, build and run tests/cmake_consumer
consumer() {
    name=$1; shift
    step "$name" cmake -S tests/cmake_consumer -B "$out/$name" \
        -Wdev -Werror=dev -Werror=deprecated -DCMAKE_C_FLAGS="$STRICT" "$@" &&
    no_warning "$name" &&
    step "$name-build" cmake --build "$out/$name" &&
    run_consumer "$name" "$out/$name/cmake_consumer"
}

# 1. The library: configured for one prefix, installed into another (the
# installed files must name the one installed into).
if step lib cmake -S . -B "$out/lib" -Wdev -Werror=dev -Werror=deprecated \
        -DCMAKE_INSTALL_PREFIX="$out/configured-prefix" && no_warning lib &&
   step lib-build cmake --build "$out/lib" &&
   step lib-install cmake --install "$out/lib" --prefix "$out/prefix"; then
    for f in include/hairfur.h share/cmake/hairfur/hairfur-config.cmake \
             share/cmake/hairfur/hairfur-config-version.cmake \
             share/cmake/hairfur/hairfur-targets.cmake \
             share/pkgconfig/hairfur.pc share/doc/hairfur/LICENSE; do
        [ -f "$out/prefix/$f" ] || bad "cmake --install wrote no $f"
    done
    cmp -s hairfur.h "$out/prefix/include/hairfur.h" ||
        bad "the installed hairfur.h differs from hairfur.h"
    [ -e "$out/configured-prefix" ] && bad "cmake --install --prefix wrote into the configured prefix"
    echo "cmake-check: cmake --install: $(cd "$out/prefix" && find . -type f | sort | sed 's|^\./||' | tr '\n' ' ')"
fi

# 2. find_package after the install, with the header's major.minor; a
# version the package does not have must be refused.
if [ -f "$out/prefix/share/cmake/hairfur/hairfur-config.cmake" ]; then
    if consumer find_package -DHAIRFUR_FROM=find_package \
           -DHAIRFUR_VERSION_WANTED="$major_minor" -DCMAKE_PREFIX_PATH="$out/prefix" \
           -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON; then
        grep -q "hairfur: $out/prefix/share/cmake/hairfur, version $version, include $out/prefix/include\$" \
            "$out/find_package.log" ||
            bad "find_package found another hairfur than $B/prefix's: $(grep 'hairfur: ' "$out/find_package.log")"
    fi
    if cmake -S tests/cmake_consumer -B "$out/find_package_99" \
           -DHAIRFUR_FROM=find_package -DHAIRFUR_VERSION_WANTED=99.0 \
           -DCMAKE_PREFIX_PATH="$out/prefix" >"$out/find_package_99.log" 2>&1; then
        bad "find_package(hairfur 99.0) was accepted by version $version"
    elif grep -q 'compatible with requested version "99.0"' "$out/find_package_99.log"; then
        echo "cmake-check: find_package(hairfur 99.0) refused, as it must be"
    else
        bad "find_package(hairfur 99.0) failed for another reason (log $B/find_package_99.log)"
    fi
fi

# 3. add_subdirectory of this checkout. A project that adds hairfur so does
# not install it (HAIRFUR_INSTALL is off there unless asked for).
if consumer add_subdirectory -DHAIRFUR_FROM=add_subdirectory -DHAIRFUR_SOURCE="$root" &&
   step add_subdirectory-install cmake --install "$out/add_subdirectory" --prefix "$out/sub-prefix" &&
   [ -e "$out/sub-prefix" ]; then
    bad "add_subdirectory: the consumer's cmake --install installs hairfur: $(find "$out/sub-prefix" -type f | head -n 3 | tr '\n' ' ')"
fi

# 4. FetchContent of an archive of this checkout (its working tree, less
# build/, out/ and .git).
if tar -cf "$out/hairfur-src.tar" --exclude=./build --exclude=./out --exclude=./.git . &&
   sha=$(sha256sum "$out/hairfur-src.tar" | cut -d' ' -f1); then
    consumer FetchContent -DHAIRFUR_FROM=FetchContent \
        -DHAIRFUR_URL="file://$out/hairfur-src.tar" -DHAIRFUR_SHA256="$sha"
else
    bad "could not archive the checkout into $B/hairfur-src.tar"
fi

# 5. pkg-config, from the cmake --install above and from make install.
# pkg_consumer NAME PREFIX: only PREFIX's hairfur.pc is seen
pc() { PKG_CONFIG_LIBDIR=$pc_dir PKG_CONFIG_PATH='' pkg-config "$@"; }
pkg_consumer() {
    pc_dir=$2/share/pkgconfig
    v=$(pc --modversion hairfur 2>&1)
    [ "$v" = "$version" ] || { bad "$1: pkg-config --modversion hairfur says '$v', not $version"; return 1; }
    if ! cflags=$(pc --cflags hairfur) || ! libs=$(pc --libs hairfur); then
        bad "$1: pkg-config --cflags/--libs hairfur failed"; return 1
    fi
    cflags=$(printf '%s' "$cflags" | sed 's/ *$//')
    [ "$cflags" = "-I$2/include" ] || bad "$1: pkg-config --cflags hairfur says '$cflags', not -I$2/include"
    # shellcheck disable=SC2086  # flags, one word each
    step "$1" cc -std=c99 $STRICT $cflags tests/cmake_consumer/main.c -o "$out/$1" $libs &&
    run_consumer "$1" "$out/$1"
}
if ! command -v pkg-config >/dev/null 2>&1; then
    echo "cmake-check: pkg-config part skipped: pkg-config is missing (Debian package pkg-config: make deps)"
else
    [ -f "$out/prefix/share/pkgconfig/hairfur.pc" ] && pkg_consumer pkgconfig_cmake "$out/prefix"
    if step make-install "${MAKE:-make}" --no-print-directory install PREFIX="$out/make-prefix"; then
        cmp -s hairfur.h "$out/make-prefix/include/hairfur.h" ||
            bad "make install: the installed hairfur.h differs from hairfur.h"
        pkg_consumer pkgconfig_make "$out/make-prefix"
    fi
fi

if [ $fail -ne 0 ]; then echo "make cmake-check: FAILED"; exit 1; fi
echo "make cmake-check: find_package, add_subdirectory, FetchContent and pkg-config" \
     "(cmake --install, make install) passed in $(($(date +%s) - start)) s"
