# Sourced by .ci/run and scripts/cost-setup.sh: what both need to install Debian 12's packages.
export DEBIAN_FRONTEND=noninteractive

# Retries a command three times: a mirror can fail for a moment.
retry() {
    for attempt in 1 2 3; do
        "$@" && return 0
        [ "$attempt" = 3 ] && return 1
        sleep 10
    done
}

# Whether a package is installed, at a version that contains $2 where given.
installed() {
    dpkg-query -W -f='${Status} ${Version}' "$1" 2>/dev/null | grep -q "install ok installed.*${2:-}"
}

# Prints, a line each, those of the packages named after `--` that are not installed; the
# packages before it must also be at backports' version (Mesa's: the drm-shim's version must be
# the drivers').
missing_packages() {
    local package backports=true
    for package in "$@"; do
        if [ "$package" = "--" ]; then
            backports=false
        elif $backports; then
            installed "$package" "~bpo12" || echo "$package"
        else
            installed "$package" || echo "$package"
        fi
    done
}

# Adds Debian 12's backports to apt's sources (Mesa 25 and its drm-shim come from there), on
# Debian 12 alone: on any other system (Ubuntu, Debian 13, ...) bookworm's backports would mix
# another release's packages into apt's sources, so it refuses, in one line naming the system,
# $1 (who asks) and $2 (what to install there instead), and exits 1.
add_backports() {
    local system
    system=$( (. /etc/os-release 2>/dev/null && echo "${ID:-unknown} ${VERSION_ID:-}") || echo unknown)
    if [ "$system" != "debian 12" ]; then
        echo "$1: this script installs Debian 12's packages, and this system is ${system% }: $2" >&2
        exit 1
    fi
    local sources=/etc/apt/sources.list.d/bookworm-backports.sources
    if [ ! -f "$sources" ]; then
        printf '%s\n' 'Types: deb' 'URIs: http://deb.debian.org/debian' \
            'Suites: bookworm-backports' 'Components: main' \
            'Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg' >"$sources"
    fi
}
