# tools/mcu/map_sizes.awk - flash and RAM of an image by origin, from its GNU
# ld link map (the input sections kept after --gc-sections). Used by run.sh
# (the self test) and fw_check.sh (the firmware images):
#
#   awk -v core=REGEX -v other=NAME -f tools/mcu/map_sizes.awk IMAGE.map
#
# An input file matching REGEX is the core's, libgcc.a is libgcc, anything
# else is NAME (the harness, the port). Prints one line per origin: flash
# (code, constants, the initial values of .data), data, bss.
function hex(s,   v, i, c) { # mawk has no strtonum
  v = 0; s = tolower(substr(s, 3))
  for (i = 1; i <= length(s); i++) { c = index("0123456789abcdef", substr(s, i, 1)) - 1; v = v * 16 + c }
  return v
}
function add(sec, size, file,   who, kind) {
  if (file ~ core) who = "core"; else if (file ~ /libgcc\.a/) who = "libgcc"; else who = other
  if (sec ~ /^\.(isr_vector|text|rodata|ARM\.exidx)/) kind = "flash"
  else if (sec ~ /^\.data/) kind = "data"
  else if (sec ~ /^\.bss/) kind = "bss"
  else return
  sum[who, kind] += hex(size)
}
/^Linker script and memory map/ { on = 1; next }
!on { next }
/^ \.[^ ]+$/ { pending = $1; next }
pending != "" && $1 ~ /^0x/ && NF == 3 { add(pending, $2, $3); pending = ""; next }
/^ \.[^ ]+ +0x/ && NF == 4 { add($1, $3, $4); pending = ""; next }
{ pending = "" }
END {
  n = split("core libgcc " other, who, " ")
  for (i = 1; i <= n; i++)
    printf "  %-8s flash %6d  data %5d  bss %5d bytes\n", who[i],
      sum[who[i], "flash"] + sum[who[i], "data"], sum[who[i], "data"], sum[who[i], "bss"]
}
