//! The parser's token stream with every name after a `.` read as an identifier. The lexer
//! reads a name as a type name once a structure of that name is declared (GLSL's grammar needs
//! it), but a field selection is never a type: `camera.mvp` stays a member's name beside a
//! `struct mvp` (GLSL ES 3.00 §4.3.7: a block's instance name scopes its members).

use glsl_lang::ast;
use glsl_lang::lexer::full::fs::{File, FileSystem, Lexer};
use glsl_lang::lexer::{HasLexerError, LangLexer, LangLexerIterator, ParseContext, ParseOptions, Token};
use glsl_lang::parse::{HasParser, LangParser};

/// A lexer's tokens, a type name that follows a `.` turned into an identifier.
struct Fields<'a, I> {
    inner: &'a mut I,
    after_dot: bool,
}

impl<I: HasLexerError> HasLexerError for Fields<'_, I> {
    type Error = I::Error;
}

impl<I: LangLexerIterator> Iterator for Fields<'_, I> {
    type Item = I::Item;

    fn next(&mut self) -> Option<Self::Item> {
        let item = self.inner.next()?;
        let after_dot = std::mem::replace(&mut self.after_dot, matches!(item, Ok((_, Token::Dot, _))));
        Some(match item {
            Ok((from, Token::TypeName(name), to)) if after_dot => Ok((from, Token::Identifier(name), to)),
            other => other,
        })
    }
}

/// Parses a preprocessed file as a translation unit, field selections read as above.
// The error is glsl-lang's own, returned as its parser gives it.
#[allow(clippy::result_large_err)]
pub(super) fn parse<'r, 'p, F: FileSystem>(
    file: File<'r, 'p, F>,
) -> Result<ast::TranslationUnit, glsl_lang::parse::ParseError<<Lexer<'r, 'p, F> as HasLexerError>::Error>> {
    let ctx = ParseContext::default();
    let mut tokens = Lexer::new(file, &ParseOptions::default()).run(ctx.clone());
    let parser = <ast::TranslationUnit as HasParser>::Parser::new();
    let parsed = LangParser::parse(&parser, ctx, &mut Fields { inner: &mut tokens, after_dot: false });
    parsed.map_err(|e| tokens.resolve_err(e))
}
