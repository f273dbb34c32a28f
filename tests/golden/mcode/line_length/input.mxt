PR "The axis has reached the end of its travel, please reset it now"
PR "End of travel"  ` this comment makes the line longer than sixty-four characters
PR "End of travel"  ` short comment
` a comment line that is longer than sixty-four characters is not reported by default
