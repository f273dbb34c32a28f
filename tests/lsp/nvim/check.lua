-- Headless Neovim as the editor: start `mcc lsp` with Neovim's built-in client, open the file
-- given on the command line, wait for the server's diagnostics, ask for a hover, and write both
-- to the JSON file named by $MCC_NVIM_OUT. Works with Neovim 0.7 (Debian's package) and later.
local out = os.getenv("MCC_NVIM_OUT")
local python = os.getenv("MCC_PYTHON")
local hover_line = tonumber(os.getenv("MCC_HOVER_LINE"))
local hover_col = tonumber(os.getenv("MCC_HOVER_COL"))
local result = { diagnostics = {}, hover = nil, error = nil }

local function finish()
  local file = io.open(out, "w")
  file:write(vim.fn.json_encode(result))
  file:close()
  vim.cmd("qa!")
end

local ok, err = pcall(function()
  local bufnr = vim.api.nvim_get_current_buf()
  local client_id = vim.lsp.start_client({
    name = "mcc",
    cmd = { python, "-m", "mcc", "lsp" },
    root_dir = vim.fn.getcwd(),
  })
  assert(client_id, "the mcc language server did not start")
  vim.lsp.buf_attach_client(bufnr, client_id)
  if os.getenv("MCC_SAVE_WITH") then
    -- Fix on save: the autocommand docs/EDITORS.md gives, then `:write` once the server has
    -- analysed the file (its diagnostics have arrived).
    dofile(os.getenv("MCC_SAVE_WITH"))
    assert(vim.wait(60000, function() return #vim.diagnostic.get(bufnr) > 0 end, 50),
           "no diagnostics from the server within 60 s")
    vim.cmd("write")
    result.saved = true
    vim.lsp.stop_client(client_id)
    return
  end
  if os.getenv("MCC_FORMAT") then
    -- Format the buffer as `:lua vim.lsp.buf.formatting_sync()` does (the server answers from its
    -- first finished analysis: ask until the edits come), apply the edits and write the file.
    local client = vim.lsp.get_client_by_id(client_id)
    -- a request sent before the server has answered `initialize` waits out its whole timeout: ask
    -- once the client is up, as a user formatting an open file does
    assert(vim.wait(60000, function() return client.initialized end, 20),
           "the mcc language server did not initialise within 60 s")
    local params = { textDocument = { uri = vim.uri_from_bufnr(bufnr) },
                     options = { tabSize = 4, insertSpaces = true } }
    local edits = nil
    for _ = 1, 120 do
      local responses = vim.lsp.buf_request_sync(bufnr, "textDocument/formatting", params, 30000)
      for _, response in pairs(responses or {}) do
        if response.result and #response.result > 0 then
          edits = response.result
        end
      end
      if edits then
        break
      end
      vim.wait(500)
    end
    assert(edits, "no formatting edits from the server within 60 s")
    vim.lsp.util.apply_text_edits(edits, bufnr, client.offset_encoding)
    vim.cmd("write")
    result.formatted = #edits
    vim.lsp.stop_client(client_id)
    return
  end
  local got = vim.wait(60000, function()
    return #vim.diagnostic.get(bufnr) > 0
  end, 50)
  assert(got, "no diagnostics from the server within 60 s")
  for _, d in ipairs(vim.diagnostic.get(bufnr)) do
    local code = d.code
    if code == nil and d.user_data and d.user_data.lsp then
      code = d.user_data.lsp.code
    end
    table.insert(result.diagnostics, { lnum = d.lnum, col = d.col, message = d.message,
                                       severity = d.severity, source = d.source, code = code })
  end
  local params = { textDocument = { uri = vim.uri_from_bufnr(bufnr) },
                   position = { line = hover_line, character = hover_col } }
  -- The server answers hover from its latest finished analysis; on a loaded machine the first
  -- diagnostics can arrive before that analysis is stored, so ask again until it answers.
  for _ = 1, 60 do
    local responses = vim.lsp.buf_request_sync(bufnr, "textDocument/hover", params, 30000)
    for _, response in pairs(responses or {}) do
      if response.result and response.result.contents then
        result.hover = response.result.contents.value or response.result.contents
      end
    end
    if result.hover and result.hover ~= "" then
      break
    end
    vim.wait(500)
  end
  vim.lsp.stop_client(client_id)
end)
if not ok then
  result.error = tostring(err)
end
finish()
