# Embeds one text file (IN) as a NUL-terminated char array named SYMBOL in OUT_C.
file(READ ${IN} hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," hex "${hex}")
file(WRITE ${OUT_C}.tmp "/* generated from ${IN} by tools/embed_text.cmake */\nconst char ${SYMBOL}[] = {${hex}0x00};\n")
file(COPY_FILE ${OUT_C}.tmp ${OUT_C} ONLY_IF_DIFFERENT)
