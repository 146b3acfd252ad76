#!/usr/bin/env bash
# make-pki.sh OUT_DIR [--ca-name NAME] [--access FILE] [--install-dir DIR] [--revoke NAME]...
#
# Makes (or brings up to date) the DDS Security material of mpgc in OUT_DIR, from access.yaml:
#   ca.pem, ca.key                       identity + permissions CA (EC prime256v1), CN = --ca-name
#   <name>.pem, <name>.key               one identity per participant, subject /C=NO/O=mpgc/CN=<name>
#   governance.xml, governance.p7s       signed governance (everything authenticated and encrypted)
#   permissions/<name>.xml, .p7s         signed permissions holding ONLY <name>'s grant
#   crl.pem                              the CA's revocation list (empty until --revoke)
#   security.xml                         Cyclone config fragment; identity = ${MPGC_SECURITY_ID}
#   ca.cnf, index.txt, crlnumber, ca.srl the CA's bookkeeping (stays with ca.key, not on hosts)
# Use: CYCLONEDDS_URI=file:///etc/net.xml,file://OUT_DIR/security.xml MPGC_SECURITY_ID=opp mpgc_opp
#
# Idempotent: an existing CA, and every certificate that still verifies against it with the right
# subject and key, are kept; a document is re-signed only when its text changed or its signature no
# longer verifies. --revoke NAME adds NAME's current certificate to crl.pem and issues it a new key
# and certificate (if NAME is still in access.yaml). --ca-name makes a CA of that name (tests make
# a second, foreign CA with it); for an existing CA it must match. --install-dir DIR writes
# security.xml for the files' place on the hosts (default: OUT_DIR itself). See README.md.
set -euo pipefail

readonly NOT_BEFORE="2024-01-01T00:00:00Z"
readonly NOT_AFTER="2036-01-01T00:00:00Z"
readonly DOMAIN_MIN=0 DOMAIN_MAX=230
readonly DEFAULT_CA_NAME="mpgc CA"

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)"
prog="make-pki.sh"

die() { echo "$prog: error: $*" >&2; exit 1; }
note() { echo "$prog: $*"; }
usage() {
  sed -n '2,20s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"
  exit "${1:-2}"
}

out="" ca_name="" access="$here/access.yaml" install=""
revoke=()
while (($#)); do
  case "$1" in
    -h|--help) usage 0 ;;
    --ca-name) (($# >= 2)) || die "--ca-name needs a value"; ca_name="$2"; shift 2 ;;
    --ca-name=*) ca_name="${1#*=}"; shift ;;
    --access) (($# >= 2)) || die "--access needs a file"; access="$2"; shift 2 ;;
    --access=*) access="${1#*=}"; shift ;;
    --install-dir) (($# >= 2)) || die "--install-dir needs a directory"; install="$2"; shift 2 ;;
    --install-dir=*) install="${1#*=}"; shift ;;
    --revoke) (($# >= 2)) || die "--revoke needs a participant name"; revoke+=("$2"); shift 2 ;;
    --revoke=*) revoke+=("${1#*=}"); shift ;;
    -*) die "unknown option '$1' (--help)" ;;
    *) [[ -z "$out" ]] || die "more than one OUT_DIR ('$out', '$1')"; out="$1"; shift ;;
  esac
done
[[ -n "$out" ]] || { echo "$prog: error: OUT_DIR missing" >&2; usage 2; }
command -v openssl >/dev/null || die "openssl not found (apt-get install openssl)"
[[ -f "$access" && -r "$access" ]] || die "access file '$access' not found or not readable"
if [[ -n "$ca_name" && ! "$ca_name" =~ ^[A-Za-z0-9][A-Za-z0-9\ ._-]{0,62}$ ]]; then
  die "--ca-name '$ca_name': use letters, digits, space, '.', '_', '-' (at most 63)"
fi

# ---- access.yaml -> "name<TAB>publish topics<TAB>subscribe topics" (space-separated) -----------
parse_access() {
  awk '
    function fail(msg) { printf "%s:%d: %s (line: \"%s\")\n", FILENAME, FNR, msg, raw > "/dev/stderr"; bad = 1; exit 1 }
    {
      raw = $0
      if ($0 ~ /\t/) fail("tab character (indent with spaces)")
      sub(/[ ]*#.*$/, "")
      if ($0 ~ /^[ ]*$/) next
    }
    /^participants:$/ { if (top) fail("second \"participants:\""); top = 1; next }
    /^  [^ ]/ {
      if (!top) fail("participant before \"participants:\"")
      if ($0 !~ /^  [a-z][a-z0-9_]*:$/) fail("expected \"  <name>:\" with name [a-z][a-z0-9_]*")
      name = substr($0, 3, length($0) - 3)
      if (name in known) fail("participant \"" name "\" listed twice")
      if (name == "ca" || name == "crl" || name == "governance" || name == "security")
        fail("participant name \"" name "\" is reserved (file name of the PKI)")
      known[name] = 1; order[++n] = name; next
    }
    /^    [^ ]/ {
      if (name == "") fail("\"publish:\"/\"subscribe:\" outside a participant")
      if ($0 !~ /^    (publish|subscribe): \[[^][]*\][ ]*$/) fail("expected \"    publish: [a, b]\" or \"    subscribe: [a]\" on one line")
      key = $0; sub(/^    /, "", key); sub(/:.*/, "", key)
      if ((name, key) in list) fail(key " given twice for " name)
      body = $0; sub(/^[^[]*\[/, "", body); sub(/\][ ]*$/, "", body)
      out = ""
      delete seen
      if (body !~ /^[ ]*$/) {
        m = split(body, parts, ",")
        for (i = 1; i <= m; i++) {
          t = parts[i]; gsub(/^[ ]+|[ ]+$/, "", t)
          if (t !~ /^[A-Za-z_][A-Za-z0-9_\/]*$/) fail("bad topic name \"" t "\" (Cyclone topic names: [A-Za-z0-9_/], not starting with a digit)")
          if (t in seen) fail("topic \"" t "\" twice in " key)
          seen[t] = 1; out = out (out == "" ? "" : " ") t
        }
      }
      list[name, key] = out; next
    }
    { fail("unexpected line (format: see the top of the access file)") }
    END {
      if (bad) exit 1
      if (!top) { printf "%s: no \"participants:\" line\n", FILENAME > "/dev/stderr"; exit 1 }
      if (n == 0) { printf "%s: no participants\n", FILENAME > "/dev/stderr"; exit 1 }
      for (i = 1; i <= n; i++) {
        p = order[i]
        if (!((p, "publish") in list) || !((p, "subscribe") in list)) {
          printf "%s: participant \"%s\" needs both \"publish:\" and \"subscribe:\" (use [] for none)\n", FILENAME, p > "/dev/stderr"; exit 1
        }
        printf "%s\t%s\t%s\n", p, list[p, "publish"], list[p, "subscribe"]
      }
    }' "$1"
}
table="$(parse_access "$access")" || die "malformed access file '$access' (see the message above)"

declare -a names=()
declare -A pubs=() subs=()
while IFS=$'\t' read -r n p s; do
  names+=("$n"); pubs[$n]="$p"; subs[$n]="$s"
done <<<"$table"

# Every granted topic must be one of mpgc's topics (a typo would silently deny), when the source
# tree is next to the script (not when the script was copied elsewhere).
topics_hpp="$here/../../common/include/mpgc/topics.hpp"
if [[ -f "$topics_hpp" ]]; then
  declare -A sys_topics=()
  while read -r t; do sys_topics[$t]=1; done < <(sed -n 's/.*constexpr const char\* k[A-Za-z]* = "\([^"]*\)".*/\1/p' "$topics_hpp")
  ((${#sys_topics[@]} > 0)) || die "no topics found in $topics_hpp"
  declare -A used=()
  for n in "${names[@]}"; do
    for t in ${pubs[$n]} ${subs[$n]}; do
      [[ -n "${sys_topics[$t]:-}" ]] || die "$access: $n: topic '$t' is not in $topics_hpp"
      used[$t]=1
    done
  done
  for t in "${!sys_topics[@]}"; do
    [[ -n "${used[$t]:-}" ]] || note "warning: topic '$t' of topics.hpp is granted to nobody"
  done
fi
for r in "${revoke[@]}"; do
  [[ "$r" =~ ^[a-z][a-z0-9_]*$ ]] || die "--revoke '$r': not a participant name"
done

# ---- OUT_DIR ------------------------------------------------------------------------------------
# The path goes into file: URIs, Cyclone's comma-separated CYCLONEDDS_URI and XML text.
check_path() { [[ "$1" =~ ^/[A-Za-z0-9._/+-]*$ ]] || die "OUT_DIR '$1' has characters that do not fit a file: URI in CYCLONEDDS_URI (use [A-Za-z0-9._/+-])"; }
[[ "$out" == /* ]] && check_path "$out" || check_path "$PWD/$out"
mkdir -p "$out/permissions" || die "cannot create '$out/permissions'"
out="$(cd "$out" && pwd -P)"
check_path "$out"
if [[ -n "$install" ]]; then
  [[ "$install" == /* ]] || die "--install-dir '$install' must be an absolute path"
  install="${install%/}"; check_path "$install"
else
  install="$out"
fi
exec 9>"$out/.make-pki.lock"
flock -w 60 9 || die "another make-pki.sh holds $out/.make-pki.lock"
tmp="$(mktemp -d "$out/.tmp.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
umask 022

ssl() {  # openssl with its output kept for the error message
  local log="$tmp/openssl.log"
  if ! openssl "$@" >"$log" 2>&1; then
    echo "$prog: error: openssl $1 failed:" >&2
    sed 's/^/    /' "$log" >&2
    exit 1
  fi
}
days_until() {  # whole days from now until $1 (an ISO date), at least 1
  local d=$(( ($(date -u -d "$1" +%s) - $(date -u +%s)) / 86400 ))
  ((d >= 1)) || die "the clock reads $(date -u +%F): $1 is past, nothing can be issued"
  echo "$d"
}
days="$(days_until "$NOT_AFTER")"  # validity of everything issued now: up to NOT_AFTER
pubkey() { openssl pkey -in "$1" -pubout 2>/dev/null || true; }
cert_pubkey() { openssl x509 -in "$1" -noout -pubkey 2>/dev/null || true; }

# ---- the CA -------------------------------------------------------------------------------------
if [[ -e "$out/ca.pem" || -e "$out/ca.key" ]]; then
  [[ -f "$out/ca.pem" ]] || die "$out/ca.key exists without ca.pem: restore ca.pem or remove the directory"
  [[ -f "$out/ca.key" ]] || die "$out/ca.pem exists without ca.key: restore ca.key (or remove the directory: every certificate changes)"
  ca_pub="$(cert_pubkey "$out/ca.pem")"
  [[ -n "$ca_pub" && "$ca_pub" == "$(pubkey "$out/ca.key")" ]] || die "$out/ca.key does not belong to $out/ca.pem"
  have_name="$(openssl x509 -in "$out/ca.pem" -noout -subject -nameopt RFC2253,sep_multiline 2>/dev/null | sed -n 's/^ *CN=//p')"
  if [[ -n "$ca_name" && "$ca_name" != "$have_name" ]]; then
    die "$out already has a CA named '$have_name', not '$ca_name' (another directory for another CA)"
  fi
  openssl x509 -in "$out/ca.pem" -noout -checkend 0 >/dev/null || die "$out/ca.pem has expired"
  note "CA '$have_name' kept"
else
  ca_name="${ca_name:-$DEFAULT_CA_NAME}"
  ssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -sha256 \
    -keyout "$tmp/ca.key" -out "$tmp/ca.pem" -days "$days" \
    -subj "/C=NO/O=mpgc/CN=$ca_name" \
    -addext "basicConstraints=critical,CA:TRUE" -addext "keyUsage=critical,digitalSignature,keyCertSign,cRLSign"
  chmod 600 "$tmp/ca.key"
  mv "$tmp/ca.key" "$out/ca.key"
  mv "$tmp/ca.pem" "$out/ca.pem"
  rm -f "$out/index.txt" "$out/index.txt.attr" "$out/crlnumber" "$out/crl.pem" "$out/ca.srl"
  note "CA '$ca_name' made"
fi

# The CA's database, for the revocation list (openssl ca).
cat >"$tmp/ca.cnf" <<EOF
# Generated by make-pki.sh: the CA database behind crl.pem.
[ ca ]
default_ca = CA_default
[ CA_default ]
dir = $out
database = $out/index.txt
crlnumber = $out/crlnumber
certificate = $out/ca.pem
private_key = $out/ca.key
default_md = sha256
default_crl_days = 30
EOF
mv "$tmp/ca.cnf" "$out/ca.cnf"
[[ -f "$out/index.txt" ]] || : >"$out/index.txt"
[[ -f "$out/index.txt.attr" ]] || echo "unique_subject = no" >"$out/index.txt.attr"
[[ -f "$out/crlnumber" ]] || echo 1000 >"$out/crlnumber"

make_crl() {  # valid as long as the permissions: an expired CRL would stop every participant
  ssl ca -config "$out/ca.cnf" -gencrl -crldays "$days" -out "$tmp/crl.pem"
  mv "$tmp/crl.pem" "$out/crl.pem"
}
crl_changed=0
for r in "${revoke[@]}"; do
  if [[ ! -f "$out/$r.pem" ]]; then die "--revoke $r: $out/$r.pem not found"; fi
  serial="$(openssl x509 -in "$out/$r.pem" -noout -serial | sed 's/^serial=//')"
  if awk -F'\t' -v s="$serial" '$1 == "R" && $4 == s { f = 1 } END { exit !f }' "$out/index.txt"; then
    note "$r (serial $serial) was already revoked"
  else
    ssl ca -config "$out/ca.cnf" -revoke "$out/$r.pem" -crl_reason keyCompromise
    note "$r revoked (serial $serial)"
  fi
  mkdir -p "$out/revoked"
  mv "$out/$r.pem" "$out/revoked/$r-$serial.pem"
  rm -f "$out/$r.key"
  crl_changed=1
done
if ((crl_changed)) || [[ ! -f "$out/crl.pem" ]] || ! openssl crl -in "$out/crl.pem" -noout -CAfile "$out/ca.pem" >/dev/null 2>&1; then
  make_crl
  note "crl.pem written ($(grep -c '^R' "$out/index.txt" || true) revoked)"
fi

# ---- identities ---------------------------------------------------------------------------------
# Existing certificates are checked in one openssl verify (chain and CRL), then per certificate
# subject, key and remaining validity; anything wrong is reported and the identity reissued.
declare -A keep=()
existing=()
for n in "${names[@]}"; do
  if [[ -f "$out/$n.pem" && -f "$out/$n.key" ]]; then existing+=("$out/$n.pem")
  elif [[ -f "$out/$n.pem" || -f "$out/$n.key" ]]; then note "reissuing $n: $n.pem or $n.key missing"; fi
done
if ((${#existing[@]})); then
  while IFS= read -r line; do
    [[ "$line" == *": OK" ]] || continue
    f="${line%: OK}"; keep[$(basename "$f" .pem)]=1
  done < <(openssl verify -CAfile "$out/ca.pem" -CRLfile "$out/crl.pem" -crl_check "${existing[@]}" 2>/dev/null || true)
fi
for f in "${existing[@]}"; do
  n="$(basename "$f" .pem)"
  if [[ -z "${keep[$n]:-}" ]]; then note "reissuing $n: $n.pem does not verify against ca.pem (or is revoked)"; continue; fi
  info="$(openssl x509 -in "$f" -noout -subject -nameopt RFC2253 -checkend $((30 * 86400)) -pubkey 2>/dev/null || true)"
  subj="$(sed -n 's/^subject=//p' <<<"$info")"
  if [[ "$subj" != "CN=$n,O=mpgc,C=NO" ]]; then note "reissuing $n: subject '$subj'"; unset "keep[$n]"
  elif ! grep -q "will not expire" <<<"$info"; then note "reissuing $n: expires within 30 days"; unset "keep[$n]"
  elif [[ "$(sed -n '/BEGIN PUBLIC KEY/,/END PUBLIC KEY/p' <<<"$info")" != "$(openssl pkey -in "$out/$n.key" -pubout 2>/dev/null)" ]]; then
    note "reissuing $n: $n.key does not belong to $n.pem"; unset "keep[$n]"
  fi
done
printf 'basicConstraints=critical,CA:FALSE\nkeyUsage=critical,digitalSignature\nsubjectKeyIdentifier=hash\nauthorityKeyIdentifier=keyid\n' >"$tmp/leaf.ext"
issued=()
for n in "${names[@]}"; do
  [[ -z "${keep[$n]:-}" ]] || continue
  ssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -sha256 \
    -keyout "$tmp/$n.key" -out "$tmp/$n.csr" -subj "/C=NO/O=mpgc/CN=$n"
  ssl x509 -req -in "$tmp/$n.csr" -CA "$out/ca.pem" -CAkey "$out/ca.key" -CAserial "$out/ca.srl" -CAcreateserial \
    -sha256 -days "$days" -extfile "$tmp/leaf.ext" -out "$tmp/$n.pem"
  chmod 600 "$tmp/$n.key"
  mv "$tmp/$n.key" "$out/$n.key"
  mv "$tmp/$n.pem" "$out/$n.pem"
  issued+=("$out/$n.pem")
done
if ((${#issued[@]})); then
  openssl verify -CAfile "$out/ca.pem" -CRLfile "$out/crl.pem" -crl_check "${issued[@]}" >"$tmp/verify.log" 2>&1 \
    || { sed 's/^/    /' "$tmp/verify.log" >&2; die "a newly issued certificate does not verify"; }
  for f in "${issued[@]}"; do note "identity $(basename "$f" .pem) issued"; done
fi

# ---- signed documents ---------------------------------------------------------------------------
# install_signed NEW_XML DEST_XML: replaces DEST_XML and signs it (DEST .p7s) unless both are
# already there, identical and validly signed by this CA.
install_signed() {
  local new="$1" xml="$2" p7s="${2%.xml}.p7s"
  if command -v xmllint >/dev/null; then
    xmllint --noout "$new" 2>"$tmp/xmllint.log" || { sed 's/^/    /' "$tmp/xmllint.log" >&2; die "generated ${xml#$out/} is not well-formed XML"; }
  fi
  if [[ -f "$xml" && -f "$p7s" ]] && cmp -s "$new" "$xml" \
     && openssl smime -verify -text -in "$p7s" -CAfile "$out/ca.pem" -out "$tmp/verified" >/dev/null 2>&1 \
     && cmp -s <(tr -d '\r' <"$tmp/verified") "$xml"; then
    return
  fi
  ssl smime -sign -text -in "$new" -out "$tmp/signed.p7s" -signer "$out/ca.pem" -inkey "$out/ca.key"
  openssl smime -verify -text -in "$tmp/signed.p7s" -CAfile "$out/ca.pem" -out /dev/null >/dev/null 2>&1 \
    || die "the new signature of ${p7s#$out/} does not verify against ca.pem"
  mv "$new" "$xml"
  mv "$tmp/signed.p7s" "$p7s"
  note "signed ${p7s#$out/}"
}
domains="<domains><id_range><min>$DOMAIN_MIN</min><max>$DOMAIN_MAX</max></id_range></domains>"

cat >"$tmp/governance.xml" <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<!-- Generated by make-pki.sh: only authenticated participants with a grant join; discovery,
     liveliness, every RTPS message and every topic's metadata and data are encrypted. -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      $domains
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>ENCRYPT</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
EOF
install_signed "$tmp/governance.xml" "$out/governance.xml"

topics_xml() {  # $1 publish|subscribe, $2 topics
  [[ -n "$2" ]] || return 0
  local t
  printf '        <%s>\n          <topics>\n' "$1"
  for t in $2; do printf '            <topic>%s</topic>\n' "$t"; done
  printf '          </topics>\n        </%s>\n' "$1"
}
for n in "${names[@]}"; do
  {
    cat <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<!-- Generated by make-pki.sh from access.yaml: $n's grant only (permissions travel in clear). -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$n">
      <subject_name>CN=$n,O=mpgc,C=NO</subject_name>
      <validity>
        <not_before>$NOT_BEFORE</not_before>
        <not_after>$NOT_AFTER</not_after>
      </validity>
EOF
    if [[ -n "${pubs[$n]}${subs[$n]}" ]]; then
      printf '      <allow_rule>\n        %s\n' "$domains"
      topics_xml publish "${pubs[$n]}"
      topics_xml subscribe "${subs[$n]}"
      printf '      </allow_rule>\n'
    fi
    cat <<EOF
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
EOF
  } >"$tmp/$n.xml"
  install_signed "$tmp/$n.xml" "$out/permissions/$n.xml"
done

# ---- the Cyclone fragment -----------------------------------------------------------------------
cat >"$tmp/security.xml" <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<!-- Generated by make-pki.sh for the files in $install. Merge after the network file, with the
     identity in the environment:
       CYCLONEDDS_URI=file:///path/net.xml,file://$install/security.xml MPGC_SECURITY_ID=<participant>
     An unset MPGC_SECURITY_ID fails participant creation on ".../MPGC_SECURITY_ID-unset.pem". -->
<CycloneDDS xmlns="https://cdds.io/config">
  <Domain Id="any">
    <Security>
      <Authentication>
        <IdentityCA>file://$install/ca.pem</IdentityCA>
        <IdentityCertificate>file://$install/\${MPGC_SECURITY_ID:-MPGC_SECURITY_ID-unset}.pem</IdentityCertificate>
        <PrivateKey>file://$install/\${MPGC_SECURITY_ID:-MPGC_SECURITY_ID-unset}.key</PrivateKey>
        <CRL>file://$install/crl.pem</CRL>
      </Authentication>
      <AccessControl>
        <Governance>file://$install/governance.p7s</Governance>
        <PermissionsCA>file://$install/ca.pem</PermissionsCA>
        <Permissions>file://$install/permissions/\${MPGC_SECURITY_ID:-MPGC_SECURITY_ID-unset}.p7s</Permissions>
      </AccessControl>
      <Cryptographic/>
    </Security>
  </Domain>
</CycloneDDS>
EOF
if command -v xmllint >/dev/null; then
  xmllint --noout "$tmp/security.xml" 2>"$tmp/xmllint.log" || { sed 's/^/    /' "$tmp/xmllint.log" >&2; die "generated security.xml is not well-formed XML"; }
fi
if ! cmp -s "$tmp/security.xml" "$out/security.xml"; then mv "$tmp/security.xml" "$out/security.xml"; note "security.xml written"; fi

# ---- final checks -------------------------------------------------------------------------------
declare -A want=()
for n in "${names[@]}"; do want[$n]=1; done
for f in "$out"/permissions/*.xml; do
  n="$(basename "$f" .xml)"
  [[ -n "${want[$n]:-}" ]] || note "warning: permissions/$n.* is not in $access any more: delete it and --revoke $n"
done
note "ready: $out (${#names[@]} participants: ${names[*]})"
