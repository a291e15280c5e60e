// The APT/CLSF statement grammar. It knows the shape of a CL file (records of a major word,
// an optional slash and comma-separated parameters, comments, free text) and nothing of
// what records mean: that is lowering's job (lower/lower*.cpp).
//
//   PARTNO text            free text after PARTNO, PPRINT, INSERT, REMARK, TPRINT
//   RAPID                  bare major word (a slash may follow: RAPID/)
//   GOTO / 1, 2., .5       major word, slash, parameters (number | word | 'string' | nothing)
//   TLON,GOFWD/ ...        words before the major word (APT motion modifiers)
//   ... (CIRCLE/ 1, 2), .. a parameter group: a name and parameters in parentheses
//   $$ anything            comment, alone or after a record
//   $$-> CSYS / 1, ...     Creo data comment: a record marked as written inside "$$->"
//
// Continuation ("$" at the end of a line) and line ends inside a record are the lexer's
// business (cl_lexer.re); the parser sees one EOL per record.
%require "3.8"
%language "c++"
%define api.namespace {clpc::grammar}
%define api.parser.class {Parser}
%define api.value.type variant
%define api.token.constructor
%define api.location.type {clpc::SourceLoc}
%define parse.error custom
%locations
%param {ParseState& st}

%code requires {
#include <string_view>
#include "support/source.h"
#include "grammar/record.h"
namespace clpc::grammar {
class ParseState;
struct MajorTok {
  MajorId id = MajorId::Unknown;
  std::string_view text;
  bool data_comment = false;
};
struct NumTok {
  double value = 0;
  std::string_view text;  // as written
};
}  // namespace clpc::grammar
}

%code {
#include "grammar/parse_state.h"
#define YYLLOC_DEFAULT(Cur, Rhs, N) \
  do { (Cur) = (N) ? YYRHSLOC(Rhs, 1) : YYRHSLOC(Rhs, 0); } while (0)
}

%token END 0 "end of file"
%token EOL "end of line"
%token SLASH "'/'"
%token LPAREN "'('"
%token RPAREN "')'"
%token <std::string_view> GROUP "'(' and a name"
%token COMMA "','"
%token <NumTok> NUMBER "number"
%token <std::string_view> WORD "word"
%token <std::string_view> STRING "quoted string"
%token <std::string_view> TEXT "text"
%token <std::string_view> COMMENT "comment"
%token <MajorTok> MAJOR "major word"
%nterm <std::string_view> comment

%%

input
  : %empty
  | input line
  ;

line
  : EOL
  | statement EOL           { st.end_statement(@2); }
  | statement comment EOL   { st.end_statement(@2); st.comment($2, @2); }
  | comment EOL             { st.comment($1, @1); }
  | error EOL               { st.recovered(); }
  ;

// A record is handed on only once its line end is shifted, so a record with a syntax error
// anywhere in it is never seen by lowering.
comment
  : COMMENT                 { $$ = $1; }
  ;

statement
  : head
  | head SLASH params       { st.slash(); }
  | head TEXT               { st.text($2); }
  ;

head
  : MAJOR                   { st.begin($1, @1); }
  | head COMMA WORD         { st.head_word($3, @3); }
  ;

// "GOTO/" has one empty parameter, which end_statement drops with the other trailing ones.
params
  : param_or_nothing
  | params COMMA param_or_nothing
  ;

param_or_nothing
  : %empty                  { st.empty(@$); }
  | param
  ;

param
  : NUMBER                  { st.number($1.value, $1.text, @1); }
  | WORD                    { st.word($1, @1, Param::Kind::Word); }
  | STRING                  { st.word($1, @1, Param::Kind::String); }
  | group_open params RPAREN { st.group_end(); }
  ;

group_open
  : GROUP                   { st.group_begin($1, @1); }
  | LPAREN                  { st.group_begin({}, @1); }
  ;

%%

namespace clpc::grammar {

void Parser::error(const location_type& loc, const std::string& msg) {
  st.syntax_error(loc, msg);
}

void Parser::report_syntax_error(const context& ctx) const {
  symbol_kind_type expected[8];
  int n = ctx.expected_tokens(expected, 8);
  std::string msg;
  symbol_kind_type found = ctx.token();
  if (found == symbol_kind::S_EOL || found == symbol_kind::S_YYEOF)
    msg = "record ends too early";
  else
    msg = std::string("unexpected ") + symbol_name(found);
  for (int i = 0; i < n; ++i) {
    msg += i == 0 ? ": expected " : (i + 1 == n ? " or " : ", ");
    msg += symbol_name(expected[i]);
  }
  st.syntax_error(ctx.location(), msg);
}

}  // namespace clpc::grammar
