// libxml2's streaming reader is iterative (its node stack is a heap array), strict
// (XML 1.0 well-formedness, no recovery) and reports line and column, so it runs
// before TinyXML, whose parser recurses once per nesting level and accepts
// unterminated comments, unquoted attributes and text after the root.

#include "xml_check.hpp"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include <libxml/xmlreader.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string_view>

#include "ferret/core/error.hpp"

namespace ferret::internal {
namespace {

struct FirstError {
  bool set = false;
  int code = 0, line = 0, column = 0;
  int open_elements = 0;  ///< elements still open when it was found
  bool had_root = false;  ///< a root element had been read
  std::string message;
};

void record_error(void* user, xmlErrorPtr error) {
  auto* first = static_cast<FirstError*>(user);
  if (first->set || error == nullptr || error->level < XML_ERR_ERROR) return;
  first->set = true;
  first->code = error->code;
  first->line = error->line;
  first->column = error->int2;
  first->message = error->message != nullptr ? error->message : "";
  if (const auto* ctxt = static_cast<const xmlParserCtxt*>(error->ctxt); ctxt != nullptr) {
    first->open_elements = ctxt->nameNr;
    first->had_root = ctxt->myDoc != nullptr && xmlDocGetRootElement(ctxt->myDoc) != nullptr;
  }
}

std::string where(int line, int column) {
  return "line " + std::to_string(line) + (column > 0 ? " column " + std::to_string(column) : "");
}

/// What a valid document has where libxml2 found this fault.
const char* expectation(int code) {
  switch (code) {
    case XML_ERR_COMMENT_NOT_FINISHED:
      return "a comment closed by -->";
    case XML_ERR_CDATA_NOT_FINISHED:
      return "a CDATA section closed by ]]>";
    case XML_ERR_DOCUMENT_END:
      return "nothing but comments and whitespace after the root element";
    case XML_ERR_DOCUMENT_EMPTY:
      return "a <robot> root element";
    case XML_ERR_ATTRIBUTE_NOT_STARTED:
    case XML_ERR_ATTRIBUTE_WITHOUT_VALUE:
    case XML_ERR_ATTRIBUTE_NOT_FINISHED:
    case XML_ERR_LT_IN_ATTRIBUTE:
      return "an attribute value in quotes (name=\"value\")";
    case XML_ERR_ATTRIBUTE_REDEFINED:
      return "each attribute at most once in an element";
    case XML_ERR_TAG_NAME_MISMATCH:
    case XML_ERR_TAG_NOT_FINISHED:
      return "an end tag matching the open element";
    case XML_ERR_GT_REQUIRED:
    case XML_ERR_LTSLASH_REQUIRED:
      return "a complete tag (ending in > or />)";
    case XML_ERR_INVALID_CHAR:
    case XML_ERR_INVALID_ENCODING:
      return "UTF-8 text of XML characters (no NUL or control bytes)";
    case XML_ERR_UNDECLARED_ENTITY:
    case XML_WAR_UNDECLARED_ENTITY:
    case XML_ERR_ENTITY_LOOP:
    case XML_ERR_ENTITY_PE_INTERNAL:
    case XML_ERR_ENTITYREF_SEMICOL_MISSING:
    case XML_ERR_ENTITY_IS_EXTERNAL:
    case XML_ERR_ENTITY_IS_PARAMETER:
    case XML_ERR_UNPARSED_ENTITY:
      return "only the predefined entities (&amp; &lt; &gt; &quot; &apos;) and character "
             "references (a URDF has no DOCTYPE)";
    default:
      return "well-formed XML 1.0";
  }
}

bool is_utf8_name(std::string_view encoding) {
  std::string lower;
  for (const char c : encoding) lower += static_cast<char>(c >= 'A' && c <= 'Z' ? c + 32 : c);
  return lower == "utf-8" || lower == "utf8" || lower == "us-ascii" || lower == "ascii";
}

/// The line of a <!DOCTYPE in the prolog (after a BOM, the XML declaration, comments,
/// processing instructions and whitespace), or 0: refused before libxml2 reads its
/// entity declarations (billion laughs, external entities).
int doctype_line(const std::string& text) {
  std::size_t i = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  for (;;) {
    while (i < text.size() &&
           (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n'))
      ++i;
    std::size_t end = std::string::npos;
    if (text.compare(i, 4, "<!--") == 0) {
      end = text.find("-->", i + 4);
      if (end != std::string::npos) end += 3;
    } else if (text.compare(i, 2, "<?") == 0) {
      end = text.find("?>", i + 2);
      if (end != std::string::npos) end += 2;
    } else if (text.compare(i, 9, "<!DOCTYPE") == 0) {
      return 1 +
             static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(i), '\n'));
    } else {
      return 0;
    }
    if (end == std::string::npos) return 0;  // unterminated: libxml2 says where
    i = end;
  }
}

/// Frees the reader on every way out, the throws included.
struct Reader {
  xmlTextReaderPtr ptr;
  ~Reader() { xmlFreeTextReader(ptr); }
};

/// Length of the valid UTF-8 sequence at `i` that a terminal shows as one character
/// (no C1 controls, no line or paragraph separators); 0 if there is none.
std::size_t shown_utf8_length(const std::string& text, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = b(i);
  const std::size_t n = c >= 0xF0 && c <= 0xF4 ? 4
                        : c >= 0xE0            ? (c < 0xF0 ? 3 : 0)
                        : c >= 0xC2            ? (c < 0xE0 ? 2 : 0)
                                               : 0;
  if (n == 0 || i + n > text.size()) return 0;
  std::uint32_t cp = c & (0xFF >> (n + 1));
  for (std::size_t k = 1; k < n; ++k) {
    if ((b(i + k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (b(i + k) & 0x3F);
  }
  const std::uint32_t min[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < min[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  if (cp < 0xA0 || cp == 0x2028 || cp == 0x2029) return 0;
  return n;
}

}  // namespace

std::string printable(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n' || c == '\r' || c == '\t') {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else if (c >= 0x20 && c < 0x7f) {
      out += text[i];
    } else if (const std::size_t n = c >= 0x80 ? shown_utf8_length(text, i) : 0; n > 0) {
      out.append(text, i, n);
      i += n - 1;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

void check_well_formed_xml(const std::string& text, const std::string& source) {
  if (text.size() > kMaxUrdfBytes)
    throw InputError(source, "", "a URDF of at most 16 MiB (16777216 bytes)",
                     std::to_string(text.size()) + " bytes");
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(source, "", "a <robot> root element", "an empty file");
  if (const int line = doctype_line(text); line > 0)
    throw InputError(source, "line " + std::to_string(line),
                     "no DOCTYPE or entity declarations (a URDF has no DTD)", "<!DOCTYPE");
  static std::once_flag init;
  std::call_once(init, [] { xmlInitParser(); });

  // BIG_LINES: node lines past 65535. NONET: never fetch; no NOENT, DTDLOAD or DTDATTR: no entity
  // is expanded and no DTD read. libxml2's own amplification guard stays on (no XML_PARSE_HUGE).
  const Reader reader{xmlReaderForMemory(
      text.data(), static_cast<int>(text.size()), nullptr, "UTF-8",
      XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_BIG_LINES)};
  if (reader.ptr == nullptr)
    throw InputError(source, "", "an XML document libxml2 can open", "none");
  FirstError first;
  xmlTextReaderSetStructuredErrorHandler(reader.ptr, record_error, &first);

  // The node's own line: the parser's position runs ahead by up to a chunk.
  auto here = [&] {
    const xmlNodePtr node = xmlTextReaderCurrentNode(reader.ptr);
    const long line = node != nullptr ? xmlGetLineNo(node) : -1;
    return line > 0 ? where(static_cast<int>(line), 0)
                    : where(xmlTextReaderGetParserLineNumber(reader.ptr), 0);
  };
  std::size_t elements = 0;
  bool encoding_checked = false;
  int status = 0;
  while ((status = xmlTextReaderRead(reader.ptr)) == 1) {
    if (!encoding_checked) {
      encoding_checked = true;
      // A declared encoding other than UTF-8 would make libxml2 decode bytes that
      // TinyXML and urdfdom then read as UTF-8.
      if (const xmlChar* enc = xmlTextReaderConstEncoding(reader.ptr);
          enc != nullptr && !is_utf8_name(reinterpret_cast<const char*>(enc)))
        throw InputError(source, "line 1", "encoding=\"UTF-8\" (or no encoding declaration)",
                         "encoding=\"" + printable(reinterpret_cast<const char*>(enc)) + "\"");
    }
    const int type = xmlTextReaderNodeType(reader.ptr);
    if (type == XML_READER_TYPE_DOCUMENT_TYPE || type == XML_READER_TYPE_ENTITY_REFERENCE ||
        type == XML_READER_TYPE_ENTITY)
      throw InputError(source, here(), "no DOCTYPE or entity declarations (a URDF has no DTD)",
                       "<!DOCTYPE");
    const int depth = xmlTextReaderDepth(reader.ptr) + 1;
    if (type != XML_READER_TYPE_ELEMENT) continue;
    // The whole file is at fault, and libxml2's node lines past 65535 are approximate.
    if (++elements > kMaxXmlElements)
      throw InputError(source, "(document)", "a URDF of at most 100000 elements", "more elements");
    if (depth > kMaxXmlDepth)
      throw InputError(
          source, here(), "elements nested at most 32 levels deep",
          "<" + printable(reinterpret_cast<const char*>(xmlTextReaderConstName(reader.ptr))) +
              "> at level " + std::to_string(depth));
  }
  if (status != 0 || first.set) {
    if (!first.set)
      throw InputError(source, here(), "well-formed XML 1.0", "a document libxml2 rejects");
    std::string expected = expectation(first.code);
    // libxml2 says "Extra content at the end" also when the document ends too early.
    if (first.code == XML_ERR_DOCUMENT_END && !first.had_root && elements == 0)
      expected = "a <robot> root element";
    else if (first.code == XML_ERR_DOCUMENT_END && first.open_elements > 0)
      expected = "a complete document (a comment, CDATA section or tag is not closed)";
    else if (first.message.find("Huge") != std::string::npos ||
             first.message.find("too big") != std::string::npos)
      expected = "text, comments and attribute values of at most 10000000 bytes each";
    throw InputError(source, where(first.line, first.column), expected, printable(first.message));
  }
  if (elements == 0) throw InputError(source, "", "a <robot> root element", "no element");
}

}  // namespace ferret::internal
