surface strings() { string a = concat ("ab", "cd"); string b = format ("x%dy", 7); Ci = color (match ("bc", a), match ("x7y", b), (a == "abcd") ? 1 : 0); }
