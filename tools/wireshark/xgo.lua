-- xgo.lua - Wireshark dissector for captures of the XGO board's serial line
-- (xgo-emu --capture, xgo-cli --capture; format in docs/capture.md):
-- link type 147 (LINKTYPE_USER0), a 5-byte pseudo-header (direction, board
-- tick), then the bytes as they went over the line.
--
-- Frames (55 00 LEN TYPE ADDR DATA... SUM 00 AA) are reassembled per
-- direction across records and shown in the record that completes them:
-- type, address with the register's name, data decoded byte by byte, the
-- checksum verified; bad frames and bytes outside any frame are flagged.
--
-- Register names and value meanings come from xgo_tables.lua, generated
-- from the core's tables at build time (tools/wireshark/gen_tables.c); keep
-- it next to this file. Use:
--   tshark -X lua_script:build/wireshark/xgo.lua -r capture.pcap
-- or copy both files into Wireshark's personal Lua plugins folder.

local script_dir = (debug.getinfo(1, "S").source:match("^@(.*[/\\])")) or ""
local ok, T = pcall(dofile, script_dir .. "xgo_tables.lua")
if not ok then
    T = { registers = {}, meanings = { mini = {}, lite = {} }, diag = {}, diag_addr = 0xC4 }
end

-- register covering each address: reg_at[a] = { name, start, width, access }
local reg_at = {}
for _, r in ipairs(T.registers) do
    for k = 0, r.width - 1 do
        if reg_at[r.addr + k] == nil then reg_at[r.addr + k] = r end
    end
end

local xgo = Proto("xgo", "XGO board serial line")

local DIRS = { [0] = "host to board", [1] = "board to host",
               [2] = "board to host, discarded (no host attached)", [3] = "note", [4] = "hang-up" }
local TYPES = { [0x00] = "write", [0x01] = "write (legacy)", [0x02] = "read", [0x12] = "reply" }

local f = {
    dir = ProtoField.uint8("xgo.direction", "Direction", base.DEC, DIRS),
    tick = ProtoField.uint32("xgo.tick", "Board tick", base.DEC),
    note = ProtoField.string("xgo.note", "Note"),
    frame = ProtoField.bytes("xgo.frame", "Frame", base.SPACE),
    len = ProtoField.uint8("xgo.len", "LEN", base.DEC),
    type = ProtoField.uint8("xgo.type", "Type", base.HEX, TYPES),
    addr = ProtoField.uint8("xgo.addr", "Address", base.HEX),
    reg = ProtoField.string("xgo.reg", "Register"),
    count = ProtoField.uint8("xgo.count", "Bytes asked", base.DEC),
    data = ProtoField.bytes("xgo.data", "Data", base.SPACE),
    value = ProtoField.string("xgo.value", "Value"),
    sum = ProtoField.uint8("xgo.checksum", "Checksum", base.HEX),
    sum_status = ProtoField.string("xgo.checksum.status", "Checksum status"),
    bad = ProtoField.string("xgo.bad", "Rejected"),
    garbage = ProtoField.bytes("xgo.garbage", "Bytes outside a frame", base.SPACE),
}
xgo.fields = { f.dir, f.tick, f.note, f.frame, f.len, f.type, f.addr, f.reg, f.count, f.data,
               f.value, f.sum, f.sum_status, f.bad, f.garbage }

local ex = {
    checksum = ProtoExpert.new("xgo.checksum.bad", "Bad checksum", expert.group.CHECKSUM, expert.severity.ERROR),
    bad = ProtoExpert.new("xgo.bad.expert", "Rejected frame", expert.group.MALFORMED, expert.severity.ERROR),
    garbage = ProtoExpert.new("xgo.garbage.expert", "Bytes outside a frame", expert.group.PROTOCOL, expert.severity.WARN),
    range = ProtoExpert.new("xgo.range.bad", "Address range past 0xFF", expert.group.MALFORMED, expert.severity.WARN),
}
xgo.experts = { ex.checksum, ex.bad, ex.garbage, ex.range }

-- state of the first pass: bytes waiting per stream, what each record completed
local pending, items, model

function xgo.init()
    pending = { host = "", board = "" }
    items = {}
    model = "mini"
end

local function checksum(s, i, len)
    local sum = 0
    for k = i + 2, i + len - 4 do sum = sum + s:byte(k) end
    return (255 - sum % 256) % 256
end

-- Cuts whole frames, rejected starts and stray bytes off stream s (a string)
-- as the board's parser would see them; returns the items and the rest.
local function scan(s, from_board)
    local out, i, stray = {}, 1, nil
    local function flush_stray(upto)
        if stray then out[#out + 1] = { kind = "garbage", bytes = s:sub(stray, upto) }; stray = nil end
    end
    while i <= #s do
        local b0, b1 = s:byte(i), s:byte(i + 1)
        if b0 ~= 0x55 or (b1 ~= nil and b1 ~= 0x00) then
            stray = stray or i
            i = i + 1
        elseif #s < i + 3 then
            break                                   -- header seen, TYPE not yet
        else
            local len, typ = s:byte(i + 2), s:byte(i + 3)
            local valid = from_board and typ == 0x12 or (not from_board and typ <= 0x02)
            local reason = (len < 9 and "bad length") or (not valid and "bad type") or
                           (typ == 0x02 and len ~= 9 and "bad length") or nil
            if reason == nil and #s < i + len - 1 then break end  -- the rest in a later record
            if reason == nil and (s:byte(i + len - 2) ~= 0x00 or s:byte(i + len - 1) ~= 0xAA) then
                reason = "bad tail"
            end
            flush_stray(i - 1)
            if reason then
                out[#out + 1] = { kind = "bad", bytes = s:sub(i, i), reason = reason }
                i = i + 1                               -- the board drops one byte and rescans
            else
                out[#out + 1] = { kind = "frame", bytes = s:sub(i, i + len - 1),
                                  sum_ok = checksum(s, i, len) == s:byte(i + len - 3) }
                i = i + len
            end
        end
    end
    flush_stray(i - 1)
    return out, s:sub(i)
end

local function to_tvb(bytes, name)
    local hex = bytes:gsub(".", function(c) return string.format("%02X", c:byte()) end)
    return ByteArray.new(hex):tvb(name)
end

-- "vx = 0xFF (+25.00 cm/s)" for data byte k of a frame at addr
local function byte_value(addr, k, b)
    local a = addr + k
    local r = reg_at[a]
    local name = r and ((r.addr == a) and r.name or string.format("%s[%d]", r.name, a - r.addr))
                 or string.format("0x%02X", a)
    local t = T.meanings[model] and T.meanings[model][a]
    local m = t and ((t.all and t.all[b + 1]) or t[b])
    return string.format("%s = 0x%02X%s", name, b, m and (" (" .. m .. ")") or "")
end

-- Views a reply may carry instead of plain bytes (docs/registers.md).
local function reply_view(t, tree, addr, n)
    if addr >= 0x62 and addr <= 0x64 and n >= 4 then
        tree:add(f.value, t(5, 4), string.format("%s = %.2f deg (float32)", reg_at[addr].name, t(5, 4):le_float()))
        return 4
    elseif addr >= 0x66 and addr <= 0x68 and n >= 2 then
        tree:add(f.value, t(5, 2), string.format("%s = %.2f deg (int16 / 100)", reg_at[addr].name, t(5, 2):int() / 100))
        return 2
    elseif addr == 0x07 then
        tree:add(f.value, t(5, math.min(n, 10)), "firmware = \"" .. t(5, math.min(n, 10)):stringz() .. "\"")
        return math.min(n, 10)
    elseif addr == T.diag_addr then
        local k = 0
        while 4 * k + 4 <= n and T.diag[k + 1] do
            tree:add(f.value, t(5 + 4 * k, 4), string.format("%s = %u", T.diag[k + 1], t(5 + 4 * k, 4):le_uint()))
            k = k + 1
        end
        return n
    end
    return 0
end

-- One frame: its fields, and a summary for the Info column.
local function show_frame(item, tree, pinfo)
    local t = to_tvb(item.bytes, "XGO frame")
    local len, typ, addr = t(2, 1):uint(), t(3, 1):uint(), t(4, 1):uint()
    local n = len - 8
    local r = reg_at[addr]
    local name = r and ((r.addr == addr) and r.name or string.format("%s[%d]", r.name, addr - r.addr)) or "-"
    local what = string.format("%s 0x%02X %s n=%d", TYPES[typ] or "?", addr, name,
                               typ == 0x02 and t(5, 1):uint() or n)
    local st = tree:add(f.frame, t()):set_text("Frame: " .. what)
    st:add(f.len, t(2, 1)); st:add(f.type, t(3, 1)); st:add(f.addr, t(4, 1))
    st:add(f.reg, t(4, 1), name)
    local span = n
    if typ == 0x02 then
        st:add(f.data, t(5, 1)); st:add(f.count, t(5, 1)); span = t(5, 1):uint()
    else
        st:add(f.data, t(5, n))
        local k = (typ == 0x12) and reply_view(t, st, addr, n) or 0
        while k < n do
            st:add(f.value, t(5 + k, 1), byte_value(addr, k, t(5 + k, 1):uint())); k = k + 1
        end
    end
    if span == 0 or span > 247 or addr + span > 256 then st:add_proto_expert_info(ex.range) end
    local sum = st:add(f.sum, t(len - 3, 1))
    st:add(f.sum_status, t(len - 3, 1), item.sum_ok and "good" or "bad")
    if not item.sum_ok then sum:add_proto_expert_info(ex.checksum) end
    return (item.sum_ok and "" or "BAD CHECKSUM ") .. what
end

local function show_items(list, tree, pinfo)
    local info = {}
    for _, item in ipairs(list) do
        if item.kind == "frame" then
            info[#info + 1] = show_frame(item, tree, pinfo)
        elseif item.kind == "bad" then
            local t = to_tvb(item.bytes, "XGO rejected")
            tree:add(f.bad, t(), item.reason):add_proto_expert_info(ex.bad)
            info[#info + 1] = "rejected (" .. item.reason .. ")"
        else
            local t = to_tvb(item.bytes, "XGO stray bytes")
            tree:add(f.garbage, t()):add_proto_expert_info(ex.garbage)
            info[#info + 1] = string.format("%d stray bytes", #item.bytes)
        end
    end
    return table.concat(info, "; ")
end

-- First pass: the record's bytes join their stream; whatever completes is
-- kept for this record (later passes only show it).
local function reassemble(num, dir, payload)
    if dir == 3 then
        model = payload:match("profile=(%a+)") or model
        return {}
    elseif dir == 4 then
        pending.host = ""                           -- the board drops the partial frame
        return {}
    end
    local key = (dir == 0) and "host" or "board"
    local list
    list, pending[key] = scan(pending[key] .. payload, key == "board")
    return list
end

function xgo.dissector(tvb, pinfo, tree)
    if tvb:len() < 5 then return 0 end
    local dir, tick = tvb(0, 1):uint(), tvb(1, 4):le_uint()
    pinfo.cols.protocol = "XGO"
    local root = tree:add(xgo, tvb())
    root:add(f.dir, tvb(0, 1))
    if tick ~= 0xFFFFFFFF then root:add_le(f.tick, tvb(1, 4)) end
    local payload = tvb:len() > 5 and tvb:raw(5, tvb:len() - 5) or ""
    if not pinfo.visited then items[pinfo.number] = reassemble(pinfo.number, dir, payload) end
    if dir == 3 then
        root:add(f.note, tvb(5))
        pinfo.cols.info = "note: " .. payload
    elseif dir == 4 then
        pinfo.cols.info = "host hung up"
    else
        local prefix = (dir == 0) and "host > board: " or ((dir == 1) and "board > host: " or "discarded: ")
        local shown = show_items(items[pinfo.number] or {}, root, pinfo)
        pinfo.cols.info = prefix .. (shown ~= "" and shown or "(part of a frame)")
    end
    return tvb:len()
end

DissectorTable.get("wtap_encap"):add(wtap.USER0, xgo)
