// `wavebench account hash` and `wavebench account add FILE NAME --role ROLE`: entries of the
// daemon's accounts file (wavebenchd --accounts). The password comes from stdin (one line), so
// it never shows in the process list or the shell's history.
#include "account_commands.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "wavebench/daemon/accounts.hpp"

namespace wavebench::cli {

namespace {

std::string password_from_stdin() {
  std::string line;
  std::getline(std::cin, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

struct AddArgs {
  std::string file;
  std::string name;
  std::string role = "operator";
};

int add_account(const AddArgs& args) {
  using namespace wavebench::daemon;
  if (!valid_account_name(args.name)) {
    std::cerr << "wavebench account add: NAME: got '" << args.name << "', expected 1 to "
              << kMaxAccountNameLength << " of A-Z a-z 0-9 . _ -\n";
    return 2;
  }
  std::vector<Account> accounts;
  if (std::filesystem::exists(args.file)) accounts = load_accounts(args.file).all();
  for (const auto& a : accounts) {
    if (a.name == args.name) {
      std::cerr << "wavebench account add: NAME: got '" << args.name
                << "', expected a name not yet in " << args.file << "\n";
      return 2;
    }
  }
  if (accounts.size() >= kMaxAccounts) {
    std::cerr << "wavebench account add: " << args.file << " holds " << kMaxAccounts
              << " accounts already (the most the daemon reads)\n";
    return 2;
  }
  Account account;
  account.name = args.name;
  account.role = args.role == "engineer" ? Role::kEngineer : Role::kOperator;
  account.password_hash = hash_password(password_from_stdin());
  accounts.push_back(account);
  const auto text = accounts_yaml(Accounts(std::move(accounts)));
  const auto temporary = args.file + ".tmp";
  // 0600: the hashes are slow to crack, not impossible; only the daemon's user reads them.
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0 || ::write(fd, text.data(), text.size()) != static_cast<ssize_t>(text.size()) ||
      ::fsync(fd) != 0 || ::close(fd) != 0) {
    std::cerr << "wavebench account add: cannot write " << temporary << "\n";
    return 1;
  }
  std::filesystem::rename(temporary, args.file);
  std::cout << "added " << account.name << " (" << role_name(account.role) << ") to " << args.file
            << "\n";
  return 0;
}

}  // namespace

void register_account_commands(CLI::App& app, ExitStatus& status) {
  auto* account = app.add_subcommand("account", "operators' accounts for wavebenchd --accounts");
  account->require_subcommand(1);
  auto* hash = account->add_subcommand(
      "hash", "read a password from stdin, print its Argon2id hash (for password_hash)");
  hash->callback([&status] {
    try {
      std::cout << daemon::hash_password(password_from_stdin()) << "\n";
    } catch (const std::invalid_argument& e) {
      std::cerr << "wavebench account hash: " << e.what() << "\n";
      status.code = 2;
    } catch (const std::exception& e) {
      std::cerr << "wavebench account hash: " << e.what() << "\n";
      status.code = 1;
    }
  });
  auto args = std::make_shared<AddArgs>();
  auto* add = account->add_subcommand(
      "add", "add NAME to the accounts FILE (created 0600 if missing); the password from stdin");
  add->add_option("file", args->file, "the accounts file")->required();
  add->add_option("name", args->name, "the operator's name")->required();
  add->add_option("--role", args->role, "operator or engineer")
      ->check(CLI::IsMember({"operator", "engineer"}))
      ->capture_default_str();
  add->callback([args, &status] {
    try {
      status.code = add_account(*args);
    } catch (const std::invalid_argument& e) {
      std::cerr << "wavebench account add: " << e.what() << "\n";
      status.code = 2;
    } catch (const std::exception& e) {
      std::cerr << "wavebench account add: " << e.what() << "\n";
      status.code = 1;
    }
  });
}

}  // namespace wavebench::cli
