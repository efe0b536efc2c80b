"""A small IEEE 1364 VCD reader, written for the tests independently of softslc's writer.

It reads what the standard's grammar allows in a four-state dump of scalars, vectors and reals
(section 18.2 of IEEE 1364-2005): declaration commands up to $enddefinitions, then `#time`,
$dumpvars/$dumpall/$dumpon/$dumpoff blocks, $comment blocks, scalar changes (`0!`, `1"`, x, z),
vector changes (`b1010 #`, left-extended with 0, or with x/z when the leftmost bit is x/z), and
real changes (`r1.5 $`). Nothing here is shared with the C++ writer.
"""

import bisect


class VcdError(Exception):
    pass


class Var:
    def __init__(self, kind, size, code, name, scope):
        self.kind, self.size, self.code, self.name, self.scope = kind, size, code, name, scope
        self.times, self.values = [], []

    def at(self, t):
        """The value in force at time t (the last change at or before t), or None before the first."""
        i = bisect.bisect_right(self.times, t)
        return None if i == 0 else self.values[i - 1]

    def changes(self):
        return list(zip(self.times, self.values))


class Vcd:
    def __init__(self, text):
        self.timescale = None
        self.vars = {}       # by reference name
        self.by_code = {}    # id code -> [Var] (several vars may share one code)
        self.comments = []
        self.times = []
        self._parse(text.split())

    def __getitem__(self, name):
        if name not in self.vars:
            raise KeyError("no signal %r in the VCD (have %s)" % (name, ", ".join(sorted(self.vars))))
        return self.vars[name]

    def _parse(self, tokens):
        i, n, scope = 0, len(tokens), []

        def until_end(i):
            body = []
            while i < n and tokens[i] != "$end":
                body.append(tokens[i])
                i += 1
            if i == n:
                raise VcdError("a declaration is missing its $end")
            return body, i + 1

        # Declarations.
        while i < n and tokens[i] != "$enddefinitions":
            tok = tokens[i]
            body, i = until_end(i + 1)
            if tok == "$timescale":
                self.timescale = "".join(body)
            elif tok == "$scope":
                scope.append(body[1])
            elif tok == "$upscope":
                scope.pop()
            elif tok == "$var":
                kind, size, code, name = body[0], int(body[1]), body[2], body[3]
                v = Var(kind, size, code, name, ".".join(scope))
                if name in self.vars:
                    raise VcdError("signal %r declared twice" % name)
                self.vars[name] = v
                self.by_code.setdefault(code, []).append(v)
            elif tok == "$comment":
                self.comments.append(" ".join(body))
            elif tok in ("$date", "$version"):
                pass
            else:
                raise VcdError("unknown declaration %s" % tok)
        if i == n:
            raise VcdError("no $enddefinitions")
        _, i = until_end(i + 1)
        if scope:
            raise VcdError("unbalanced $scope")

        # Value changes.
        now = None
        while i < n:
            tok = tokens[i]
            if tok[0] == "#":
                t = int(tok[1:])
                if now is not None and t < now:
                    raise VcdError("time goes backwards at #%d" % t)
                now = t
                self.times.append(t)
                i += 1
            elif tok == "$comment":
                body, i = until_end(i + 1)
                self.comments.append(" ".join(body))
            elif tok in ("$dumpvars", "$dumpall", "$dumpon", "$dumpoff", "$end"):
                i += 1
            elif tok[0] in "bBrR":
                if i + 1 >= n:
                    raise VcdError("a vector change without its id code")
                self._set(tokens[i + 1], tok, now)
                i += 2
            elif tok[0] in "01xXzZ":
                self._set(tok[1:], tok[0], now)
                i += 1
            else:
                raise VcdError("unexpected token %r" % tok)

    def _set(self, code, text, now):
        if now is None:
            raise VcdError("a value change before the first #time")
        if code not in self.by_code:
            raise VcdError("value change for undeclared id code %r" % code)
        for v in self.by_code[code]:
            if text[0] in "rR":
                value = float(text[1:])
            elif text[0] in "bB":
                bits = text[1:].lower()
                if any(c not in "01" for c in bits):
                    value = None  # x or z: not a number
                else:
                    if len(bits) > v.size:
                        raise VcdError("%s: %d bits for a %d-bit signal" % (v.name, len(bits), v.size))
                    value = int(bits, 2)
            else:
                value = None if text in "xXzZ" else int(text)
            if v.times and v.times[-1] == now:
                v.values[-1] = value  # a later change at the same time wins
            else:
                v.times.append(now)
                v.values.append(value)


def signed(value, bits):
    """Two's complement reading of an unsigned vector value."""
    return value - (1 << bits) if value is not None and value >= 1 << (bits - 1) else value


def first_time(var, predicate, after=-1):
    """The first change time > after at which predicate(value) holds, or None."""
    for t, v in var.changes():
        if t > after and v is not None and predicate(v):
            return t
    return None
